//! spintop's benchmarks (`cargo bench -p spintop-benches --bench NAME`): the
//! targets are the files beside this one; this library is empty, only so
//! that Cargo has a package to hang them on. The package is kept out of
//! spintop's own so that `cargo test` never builds criterion or the peers.

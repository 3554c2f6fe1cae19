//! What the machine must give a grading, and what to say when it does not:
//! a `cargo` this user may run, a toolchain it can choose, the crates it
//! builds against (offline), a folder it may write. Each is a failure of
//! the grading ([`CourseError::CannotGrade`]), never a state of the
//! student's code, said with what to do about it.

use super::CourseError;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// The cargo a grading runs: the one running us (`CARGO`, as under `cargo
/// run`), else the first `cargo` on `PATH` that this user may run; or why
/// there is none, and what to do.
pub fn find_cargo() -> Result<PathBuf, CourseError> {
    find_cargo_in(
        std::env::var_os("CARGO"),
        std::env::var_os("PATH").unwrap_or_default(),
    )
}

/// [`find_cargo`] with `CARGO` and `PATH` given.
pub(crate) fn find_cargo_in(
    cargo: Option<OsString>,
    path: OsString,
) -> Result<PathBuf, CourseError> {
    const INSTALL: &str = "install Rust for this user (https://rustup.rs), or put the folder holding cargo (usually ~/.cargo/bin) on PATH, then grade again";
    if let Some(c) = cargo.filter(|c| !c.is_empty()) {
        let c = PathBuf::from(c);
        return match runnable(&c) {
            Ok(()) => Ok(c),
            Err(why) => Err(CourseError::CannotGrade(format!(
                "CARGO names {}, which {why}: unset CARGO, or {INSTALL}",
                c.display()
            ))),
        };
    }
    let mut blocked = Vec::new();
    for dir in std::env::split_paths(&path).filter(|d| !d.as_os_str().is_empty()) {
        let candidate = dir.join(exe("cargo"));
        match runnable(&candidate) {
            Ok(()) => return Ok(candidate),
            Err(why) if why != NOT_THERE => blocked.push(format!("{} {why}", candidate.display())),
            Err(_) => {}
        }
    }
    let shown = path.to_string_lossy();
    Err(CourseError::CannotGrade(match blocked.first() {
        None => format!(
            "cargo was not found: no folder on PATH ({shown}) holds it, and spintop grades by building the course with cargo; {INSTALL}"
        ),
        Some(first) => format!(
            "cargo cannot be run by this user ({}): {first}; {INSTALL}",
            whoami()
        ),
    }))
}

const NOT_THERE: &str = "does not exist";

fn exe(name: &str) -> String {
    format!("{name}{}", std::env::consts::EXE_SUFFIX)
}

/// Whether this user may run the program at `path`, or why not, in words.
fn runnable(path: &Path) -> Result<(), String> {
    match std::fs::metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Err(NOT_THERE.into()),
        Err(e) => {
            return Err(format!(
                "cannot be reached: {}",
                refused_by(path, &e, "not open to")
            ));
        }
        Ok(m) if !m.is_file() => return Err("is not a program".into()),
        Ok(_) => {}
    }
    #[cfg(unix)]
    if let Err(e) = rustix::fs::access(path, rustix::fs::Access::EXEC_OK) {
        return Err(format!("may not be run: {}", std::io::Error::from(e)));
    }
    Ok(())
}

/// "nobody (uid 65534)": who this process runs as.
fn whoami() -> String {
    #[cfg(unix)]
    {
        let uid = rustix::process::geteuid().as_raw();
        match user_name(uid) {
            Some(name) => format!("{name} (uid {uid})"),
            None => format!("uid {uid}"),
        }
    }
    #[cfg(not(unix))]
    {
        "this user".to_string()
    }
}

/// The name `/etc/passwd` gives the user `uid`, if it names one.
#[cfg(unix)]
fn user_name(uid: u32) -> Option<String> {
    let text = std::fs::read_to_string("/etc/passwd").ok()?;
    text.lines().find_map(|l| {
        let mut f = l.split(':');
        let name = f.next()?;
        (f.nth(1)?.parse::<u32>().ok()? == uid).then(|| name.to_string())
    })
}

/// Why `path` could not be written (or reached), in words a student can act
/// on: the folder that refuses, whose it is and who we are, or a read-only
/// file system; else the system's own words.
pub fn unwritable_why(path: &Path, e: &std::io::Error) -> String {
    refused_by(path, e, "not writable by")
}

/// Why `path` was refused (`e`): the folder that refuses and whose it is,
/// and what it is to this user (`act`: "not writable by", "not open to").
fn refused_by(path: &Path, e: &std::io::Error, act: &str) -> String {
    #[cfg(not(unix))]
    let _ = (path, act);
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let read_only = e.raw_os_error() == Some(30); // EROFS
        if read_only {
            return "the file system it is on is read-only".to_string();
        }
        if e.kind() == std::io::ErrorKind::PermissionDenied {
            // The nearest folder that exists is the one that refuses.
            let folder = path
                .ancestors()
                .skip(1)
                .find_map(|d| std::fs::metadata(d).ok().map(|m| (d, m)));
            if let Some((dir, meta)) = folder {
                let owner = user_name(meta.uid()).unwrap_or_else(|| format!("uid {}", meta.uid()));
                // The path is named already: its folder by name alone.
                let shown = match dir.file_name() {
                    Some(name) => format!("its folder {}/", name.to_string_lossy()),
                    None => dir.display().to_string(),
                };
                return format!(
                    "{shown} is {owner}'s (mode {:o}), {act} {}",
                    meta.mode() & 0o7777,
                    whoami(),
                );
            }
        }
    }
    e.to_string()
}

/// What a grading says when cargo stopped before compiling any of the
/// student's code (no toolchain chosen, crates missing offline, no
/// linker): cargo's own line quoted, and what to do.
pub(crate) fn refusal(line: &str) -> String {
    let l = line.to_lowercase();
    let toolchain =
        "install a Rust toolchain or choose one (`rustup default stable`; https://rustup.rs)";
    let fetch = "grading builds offline: run `cargo fetch` once in the course's folder while online, so that the crates it needs are in cargo's cache";
    let advice = if l.contains("rustup") || l.contains("toolchain") {
        toolchain.to_string()
    } else if [
        "offline",
        "download",
        "no matching package",
        "failed to get",
        "failed to load source",
        "registry",
        "index",
    ]
    .iter()
    .any(|w| l.contains(w))
    {
        fetch.to_string()
    } else if l.contains("linker") || l.contains("linking") {
        "install a C linker (`cc`: e.g. the build-essential package), which Rust links programs with".to_string()
    } else {
        format!("{toolchain}; and {fetch}")
    };
    format!(
        "cargo stopped before compiling any of the course's code (\"{}\"): it is this machine's setup, not the code: {advice}",
        line.trim()
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("spintop-toolchain-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn no_cargo_on_path_says_so_and_what_to_install() {
        let dir = scratch("none");
        let e = find_cargo_in(None, dir.clone().into_os_string()).unwrap_err();
        let said = e.to_string();
        assert!(matches!(e, CourseError::CannotGrade(_)));
        assert!(said.contains("cargo was not found"), "{said}");
        assert!(
            said.contains(&dir.display().to_string()),
            "the PATH searched: {said}"
        );
        assert!(
            said.contains("rustup.rs") && said.contains("PATH"),
            "{said}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[cfg(unix)]
    #[test]
    fn a_cargo_on_path_is_found_and_one_not_runnable_is_named() {
        use std::os::unix::fs::PermissionsExt;
        let (a, b) = (scratch("a"), scratch("b"));
        let cargo = b.join("cargo");
        std::fs::write(&cargo, "#!/bin/sh\n").unwrap();
        std::fs::set_permissions(&cargo, std::fs::Permissions::from_mode(0o755)).unwrap();
        let path = std::env::join_paths([&a, &b]).unwrap();
        assert_eq!(find_cargo_in(None, path.clone()).unwrap(), cargo);
        // Not executable (for root too: no x bit at all).
        std::fs::set_permissions(&cargo, std::fs::Permissions::from_mode(0o644)).unwrap();
        let said = find_cargo_in(None, path).unwrap_err().to_string();
        assert!(
            said.contains("cannot be run by this user")
                && said.contains(&cargo.display().to_string()),
            "{said}"
        );
        // CARGO naming nothing is said as such.
        let said = find_cargo_in(Some(a.join("nope").into()), OsString::new())
            .unwrap_err()
            .to_string();
        assert!(
            said.contains("CARGO names") && said.contains("does not exist"),
            "{said}"
        );
        let _ = std::fs::remove_dir_all(&a);
        let _ = std::fs::remove_dir_all(&b);
    }

    #[test]
    fn each_refusal_quotes_cargo_and_gives_the_advice_that_fits() {
        let rustup = "error: rustup could not choose a version of cargo to run, because one wasn't specified explicitly, and no default is configured.";
        let said = refusal(rustup);
        assert!(
            said.contains(rustup) && said.contains("rustup default stable"),
            "{said}"
        );
        assert!(!said.contains("cargo fetch"), "{said}");
        let offline = "error: no matching package named `nalgebra` found";
        let said = refusal(offline);
        assert!(
            said.contains(offline) && said.contains("cargo fetch"),
            "{said}"
        );
        let said = refusal("error: linker `cc` not found");
        assert!(said.contains("C linker"), "{said}");
        let said = refusal("error: something else");
        assert!(
            said.contains("cargo fetch") && said.contains("rustup"),
            "{said}"
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_read_only_or_foreign_folder_is_named_with_its_owner() {
        let e = std::io::Error::from_raw_os_error(13);
        let said = unwritable_why(Path::new("/proc/1/nope/file"), &e);
        assert!(
            said.contains("its folder 1/ is root's (mode 555), not writable by"),
            "{said}"
        );
        assert!(said.contains("uid 0"), "{said}");
        let e = std::io::Error::from_raw_os_error(30);
        assert!(unwritable_why(Path::new("/x"), &e).contains("read-only"));
        let e = std::io::Error::from_raw_os_error(2);
        assert_eq!(unwritable_why(Path::new("/x"), &e), e.to_string());
    }
}

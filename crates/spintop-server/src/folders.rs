//! The folders the server trusts are the reader's own: the built book it
//! serves (its pages receive the token), the scratch project it compiles
//! (a `build.rs` there runs as the reader) and the build folder whose
//! programs it runs. Another user who could write one of them, or rename a
//! folder above one, could have the reader's browser run their page with
//! the token, or the reader's build run their code.
//!
//! The rule is OpenSSH's `StrictModes` and Jupyter's for its runtime
//! folder: the folder is the reader's, and neither it nor any folder above
//! it may be written by another user (group or others) or belong to one
//! (root aside, who can do anything anyway). One exception, as for `/tmp`:
//! a folder above that others may write but that has the sticky bit, where
//! only an entry's owner may rename or remove it, provided the next folder
//! down is the reader's (or root's). The path is resolved once
//! ([`std::fs::canonicalize`]) and used resolved, so that no symbolic link
//! can be swapped under it afterwards.
//!
//! The scratch folder is made fresh at each start, mode 0700: an old one is
//! removed only if it is a scratch project of `spintop book` (or empty),
//! never another folder a reader named by mistake.

use std::fs::Metadata;
use std::os::unix::fs::{DirBuilderExt, MetadataExt, PermissionsExt};
use std::path::{Path, PathBuf};

/// Why a folder is not trusted, said to the reader in one line.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{what} {path}: {why}")]
pub struct Untrusted {
    /// What the folder is for ("--site", "--scratch", "the build folder").
    pub what: String,
    /// The folder, as given.
    pub path: PathBuf,
    /// Why, and what to do.
    pub why: String,
}

/// What another user could do with a folder the server trusts, by use.
fn risk(what: &str) -> &'static str {
    match what {
        "--site" => "their pages would receive the book's token and run in your browser",
        "--scratch" => "they could plant code that the build runs as you",
        _ => "they could replace the programs it runs as you",
    }
}

/// The verdict on one folder of the chain: `meta`'s owner and mode, for
/// the reader `me`, the folder itself if `last`. `None` if it may be
/// trusted. (Below a sticky folder, the next one down must then be the
/// reader's or root's, as every folder of the chain must.)
fn verdict(meta: &Metadata, me: u32, last: bool) -> Option<String> {
    let owner = meta.uid();
    let mode = meta.permissions().mode();
    let own = owner == me || (owner == 0 && !last);
    if !own {
        return Some(format!(
            "belongs to uid {owner}, not to you (uid {me}); use a folder of your own"
        ));
    }
    let sticky = mode & 0o1000 != 0;
    if mode & 0o022 != 0 && (last || !sticky) {
        let who = if mode & 0o002 != 0 {
            "every user"
        } else {
            "its group"
        };
        return Some(format!(
            "can be written by {who} (mode {:04o}); make it yours alone (chmod go-w) or use another",
            mode & 0o7777
        ));
    }
    None
}

/// Checks that `dir` (which exists) and every folder above it may be
/// trusted (see the module's docs); returns it resolved.
pub fn check(what: &str, dir: &Path) -> Result<PathBuf, Untrusted> {
    check_chain(what, dir, true)
}

/// [`check`], `dir` itself judged as the folder trusted (`is_folder`) or
/// as one above it (the scratch folder's parent: the scratch is made in it
/// by the server, mode 0700).
fn check_chain(what: &str, dir: &Path, is_folder: bool) -> Result<PathBuf, Untrusted> {
    // `above`: the folder above `dir` that fails, `None` for `dir` itself.
    let untrusted = |above: Option<&Path>, why: String| Untrusted {
        what: what.to_string(),
        path: dir.to_path_buf(),
        why: match above {
            None => format!("{why}: {}", risk(what)),
            Some(path) => format!("{} above it {why}: {}", path.display(), risk(what)),
        },
    };
    let resolved =
        std::fs::canonicalize(dir).map_err(|e| untrusted(None, format!("cannot be read ({e})")))?;
    let me = rustix::process::geteuid().as_raw();
    let chain: Vec<&Path> = resolved.ancestors().collect();
    for (i, folder) in chain.iter().rev().enumerate() {
        let last = is_folder && i + 1 == chain.len();
        let at = (!last).then_some(*folder);
        let meta = std::fs::metadata(folder)
            .map_err(|e| untrusted(at, format!("cannot be read ({e})")))?;
        if !meta.is_dir() {
            return Err(untrusted(at, "is not a folder".into()));
        }
        if let Some(why) = verdict(&meta, me, last) {
            return Err(untrusted(at, why));
        }
    }
    Ok(resolved)
}

/// Makes `scratch` fresh, mode 0700, in a folder that may be trusted;
/// returns it resolved. An existing one is removed first if it is a
/// scratch project of `spintop book` or empty; anything else is refused.
pub fn fresh_scratch(scratch: &Path) -> Result<PathBuf, Untrusted> {
    let refuse = |why: String| Untrusted {
        what: "--scratch".into(),
        path: scratch.to_path_buf(),
        why,
    };
    let name = scratch
        .file_name()
        .ok_or_else(|| refuse("names no folder".into()))?;
    let parent = match scratch.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(parent)
        .map_err(|e| refuse(format!("cannot make the folder above it: {e}")))?;
    let parent = check_chain("--scratch", parent, false).map_err(|mut e| {
        e.path = scratch.to_path_buf();
        e
    })?;
    let resolved = parent.join(name);
    let me = rustix::process::geteuid().as_raw();
    match std::fs::symlink_metadata(&resolved) {
        Err(_) => {}
        Ok(meta) if meta.uid() != me => {
            return Err(refuse(format!(
                "belongs to uid {}, not to you (uid {me}); name a folder of your own",
                meta.uid()
            )));
        }
        Ok(meta) if meta.is_dir() && is_old_scratch(&resolved) => {
            std::fs::remove_dir_all(&resolved)
                .map_err(|e| refuse(format!("cannot remove the old scratch project: {e}")))?;
        }
        Ok(_) => {
            return Err(refuse(
                "exists and is not a scratch project of spintop book: name a new folder, or remove it".into(),
            ));
        }
    }
    std::fs::DirBuilder::new()
        .mode(0o700)
        .create(&resolved)
        .map_err(|e| refuse(format!("cannot be made: {e}")))?;
    Ok(resolved)
}

/// Whether `dir` is a folder `spintop book` made (its manifest names a
/// snippet package), or empty.
fn is_old_scratch(dir: &Path) -> bool {
    let empty = std::fs::read_dir(dir).is_ok_and(|mut d| d.next().is_none());
    let ours = std::fs::read_to_string(dir.join("Cargo.toml"))
        .is_ok_and(|m| m.starts_with("[package]\nname = \"spintop-snippet-"));
    empty || ours
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The metadata of a real folder with `mode`, owned by this process.
    fn folder(root: &Path, name: &str, mode: u32) -> Metadata {
        let dir = root.join(name);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(mode)).unwrap();
        std::fs::metadata(&dir).unwrap()
    }

    #[test]
    fn a_folder_others_may_write_is_refused_unless_sticky_above_ones_own() {
        let root = std::env::temp_dir().join(format!("spintop-folders-{}", std::process::id()));
        let me = rustix::process::geteuid().as_raw();
        let other = me + 1;
        let private = folder(&root, "private", 0o700);
        assert_eq!(verdict(&private, me, true), None);
        assert_eq!(verdict(&folder(&root, "shared", 0o755), me, true), None);
        for mode in [0o777, 0o775, 0o1777] {
            let open = folder(&root, &format!("open{mode:o}"), mode);
            let why = verdict(&open, me, true).expect("refused");
            assert!(why.contains("can be written by"), "{why}");
            // Above the folder: only a sticky one passes.
            assert_eq!(verdict(&open, me, false).is_none(), mode == 0o1777);
        }
        // Another user's folder: never the folder itself; above it, only
        // if that user is root.
        let why = verdict(&private, other, true).expect("refused");
        assert!(why.contains(&format!("belongs to uid {me}")), "{why}");
        assert_eq!(verdict(&private, other, false).is_none(), me == 0);
        std::fs::remove_dir_all(&root).unwrap();
    }
}

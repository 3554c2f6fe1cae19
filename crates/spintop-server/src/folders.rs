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
//! (root aside, who can do anything anyway). A folder its group may write
//! is the reader's alone if that group is: the reader's private group
//! (Debian, Ubuntu and Fedora give each user one and a umask of 002, so a
//! clone's folders are group-writable), with no other member in
//! `/etc/group` nor any other user's primary group in `/etc/passwd`
//! (Debian's OpenSSH takes the same rule for StrictModes). A group known
//! only to a directory service (LDAP) is not read, and refused. One
//! exception, as for `/tmp`:
//! a folder above that others may write but that has the sticky bit, where
//! only an entry's owner may rename or remove it, provided the next folder
//! down is the reader's (or root's). The path is resolved once
//! ([`std::fs::canonicalize`]) and used resolved, so that no symbolic link
//! can be swapped under it afterwards.
//!
//! The scratch folder is made fresh at each start, mode 0700: an old one is
//! removed only if it is a scratch project of `spintop book` (or empty),
//! never another folder a reader named by mistake. Each server holds its
//! scratch folder for as long as it lives (a lock, [`claim_scratch`]): two
//! servers started with the same one (two `spintop book` in one clone)
//! each get a folder of their own, and with it a program name of their
//! own, so that neither removes the other's project nor runs its snippet.

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
    let others = mode & 0o002 != 0;
    let group = mode & 0o020 != 0 && !group_is_alone(meta.gid(), me);
    if (others || group) && (last || !sticky) {
        let who = if others {
            "every user".to_string()
        } else {
            format!("its group (gid {}, not yours alone)", meta.gid())
        };
        return Some(format!(
            "can be written by {who} (mode {:04o}); make it yours alone (chmod go-w) or use another",
            mode & 0o7777
        ));
    }
    None
}

/// Whether group `gid` is the user `me`'s alone, by `/etc/group` and
/// `/etc/passwd` (see the module's docs).
fn group_is_alone(gid: u32, me: u32) -> bool {
    let read = |path| std::fs::read_to_string(path).unwrap_or_default();
    sole_member(&read("/etc/group"), &read("/etc/passwd"), gid, me)
}

/// Whether group `gid` of the `groups` table (`/etc/group`'s lines) has
/// user `me` of the `users` table (`/etc/passwd`'s) as its one member:
/// every user whose primary group it is, and every member it lists, is
/// `me`, and there is at least one. A group not in the table is not.
fn sole_member(groups: &str, users: &str, gid: u32, me: u32) -> bool {
    let fields = |line: &'_ str| line.split(':').map(str::to_string).collect::<Vec<_>>();
    let Some(listed) = groups
        .lines()
        .map(fields)
        .find(|f| f.len() >= 4 && f[2].parse() == Ok(gid))
        .map(|f| f[3].clone())
    else {
        return false;
    };
    // Name, uid and primary gid of each user.
    let users: Vec<(String, Option<u32>, Option<u32>)> = users
        .lines()
        .map(fields)
        .filter(|f| f.len() >= 4)
        .map(|f| (f[0].clone(), f[2].parse().ok(), f[3].parse().ok()))
        .collect();
    let primary: Vec<_> = users.iter().filter(|u| u.2 == Some(gid)).collect();
    let is_me = |name: &str| users.iter().any(|u| u.0 == name && u.1 == Some(me));
    let listed: Vec<&str> = listed.split(',').filter(|m| !m.is_empty()).collect();
    primary.iter().all(|u| u.1 == Some(me))
        && listed.iter().all(|m| is_me(m))
        && primary.len() + listed.len() > 0
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

/// A scratch folder this server holds: the lock on `NAME.lock` beside it
/// (an open file description of this process's, not inherited by what it
/// runs), released when the server ends, however it ends (the kernel drops
/// a dead process's locks).
#[derive(Debug)]
pub struct Scratch {
    /// The folder, resolved.
    pub path: PathBuf,
    _lock: std::fs::File,
}

/// How many servers at once may each have a scratch folder beside the one
/// named: `NAME`, then `NAME-2` up to `NAME-16`.
const SLOTS: usize = 16;

/// Claims a scratch folder for this server: `scratch` if no other living
/// server holds it, else the first of `scratch-2`, `scratch-3`, … that none
/// holds; then makes it fresh, mode 0700, in a folder that may be trusted
/// (see [`fresh_scratch`]).
pub fn claim_scratch(scratch: &Path) -> Result<Scratch, Untrusted> {
    use rustix::fs::{FlockOperation, flock};
    use std::os::unix::fs::OpenOptionsExt;
    let refuse = |why: String| Untrusted {
        what: "--scratch".into(),
        path: scratch.to_path_buf(),
        why,
    };
    let name = scratch
        .file_name()
        .ok_or_else(|| refuse("names no folder".into()))?
        .to_string_lossy()
        .into_owned();
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
    let me = rustix::process::geteuid().as_raw();
    for slot in 1..=SLOTS {
        let name = match slot {
            1 => name.clone(),
            n => format!("{name}-{n}"),
        };
        let lock = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .mode(0o600)
            // In a sticky folder (/tmp) another user may have put a link
            // or a file of theirs there first.
            .custom_flags(rustix::fs::OFlags::NOFOLLOW.bits() as i32)
            .open(parent.join(format!("{name}.lock")))
            .map_err(|e| refuse(format!("cannot make its lock file {name}.lock: {e}")))?;
        let owner = lock.metadata().map(|m| m.uid()).unwrap_or(u32::MAX);
        if owner != me {
            return Err(refuse(format!(
                "its lock file {name}.lock belongs to uid {owner}, not to you (uid {me}); name a folder of your own"
            )));
        }
        match flock(&lock, FlockOperation::NonBlockingLockExclusive) {
            Ok(()) => {}
            // Another server's.
            Err(rustix::io::Errno::WOULDBLOCK) => continue,
            Err(e) => return Err(refuse(format!("cannot lock it: {e}"))),
        }
        let path = fresh_scratch(&parent.join(&name), scratch, slot > 1)?;
        return Ok(Scratch { path, _lock: lock });
    }
    Err(refuse(format!(
        "{SLOTS} other spintop book servers hold it and the folders beside it; stop one, or name another --scratch"
    )))
}

/// Makes `resolved` (in a folder checked already) fresh, mode 0700, for
/// `--scratch asked` (`another`: beside it, since another server holds
/// `asked`); returns it. An existing one is removed first if it
/// is a scratch project of `spintop book` or empty; anything else is
/// refused. The caller holds its lock: no living server uses it.
fn fresh_scratch(resolved: &Path, asked: &Path, another: bool) -> Result<PathBuf, Untrusted> {
    let refuse = |why: String| Untrusted {
        what: "--scratch".into(),
        path: asked.to_path_buf(),
        why: match another {
            false => why,
            true => format!(
                "{} (beside it, since another spintop book holds it) {why}",
                resolved.display()
            ),
        },
    };
    let me = rustix::process::geteuid().as_raw();
    match std::fs::symlink_metadata(resolved) {
        Err(_) => {}
        Ok(meta) if meta.uid() != me => {
            return Err(refuse(format!(
                "belongs to uid {}, not to you (uid {me}); name a folder of your own",
                meta.uid()
            )));
        }
        Ok(meta) if meta.is_dir() && is_old_scratch(resolved) => {
            std::fs::remove_dir_all(resolved)
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
        .create(resolved)
        .map_err(|e| refuse(format!("cannot be made: {e}")))?;
    Ok(resolved.to_path_buf())
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

    /// Debian's OpenSSH rule: a group is one user's alone if it is the
    /// primary group of that user only and lists no one else.
    #[test]
    fn a_private_group_is_its_users_alone_and_a_shared_one_is_not() {
        let users = "root:x:0:0::/root:/bin/sh\nalice:x:1000:1000::/home/alice:/bin/sh\nbob:x:1001:1001::/home/bob:/bin/sh\ncarol:x:1002:1000::/home/carol:/bin/sh\ndave:x:1003:1003::/:/bin/sh\n";
        let groups = "root:x:0:\nalice:x:1000:\nbob:x:1001:\nstaff:x:50:alice\nclass:x:60:alice,bob\nempty:x:70:\ndave:x:1003:dave\nbobs:x:80:bob\n";
        // A private group, as useradd makes it.
        assert!(sole_member(groups, users, 1001, 1001));
        assert!(sole_member(groups, users, 1003, 1003));
        assert!(sole_member(groups, users, 0, 0));
        // Another user's, or one that lists only another user.
        assert!(!sole_member(groups, users, 1001, 1000));
        assert!(!sole_member(groups, users, 80, 1000));
        // alice's primary group is carol's too.
        assert!(!sole_member(groups, users, 1000, 1000));
        // Listing only alice: hers; listing bob too: not.
        assert!(sole_member(groups, users, 50, 1000));
        assert!(!sole_member(groups, users, 60, 1000));
        // No member at all, or no such group: not.
        assert!(!sole_member(groups, users, 70, 1000));
        assert!(!sole_member(groups, users, 99, 1000));
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
            // Writable by its group only, that group this user's alone.
            let alone = mode == 0o775 && group_is_alone(open.gid(), me);
            match verdict(&open, me, true) {
                None => assert!(alone, "{mode:o} taken"),
                Some(why) => assert!(!alone && why.contains("can be written by"), "{why}"),
            }
            // Above the folder: only a sticky one passes.
            assert_eq!(verdict(&open, me, false).is_none(), mode == 0o1777 || alone);
        }
        // As root: a folder its group may write, that group another
        // user's (uid 65534's primary group, as a class's shared group).
        if me == 0 {
            let theirs = root.join("group");
            let _ = folder(&root, "group", 0o775);
            std::os::unix::fs::chown(&theirs, None, Some(65534)).unwrap();
            let meta = std::fs::metadata(&theirs).unwrap();
            assert!(!group_is_alone(65534, me));
            let why = verdict(&meta, me, true).expect("refused");
            assert!(
                why.contains("its group (gid 65534, not yours alone)"),
                "{why}"
            );
        }
        // Another user's folder: never the folder itself; above it, only
        // if that user is root.
        let why = verdict(&private, other, true).expect("refused");
        assert!(why.contains(&format!("belongs to uid {me}")), "{why}");
        assert_eq!(verdict(&private, other, false).is_none(), me == 0);
        std::fs::remove_dir_all(&root).unwrap();
    }

    /// Two servers at once with one scratch folder each get their own: the
    /// second takes the folder beside it, leaves the first's project alone,
    /// and once the first is gone (its lock with it), the next server takes
    /// the first folder again, fresh.
    #[test]
    fn a_scratch_folder_held_by_a_living_server_is_not_taken_by_another() {
        let root = std::env::temp_dir().join(format!("spintop-claims-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        std::fs::create_dir_all(&root).unwrap();
        let asked = root.join("scratch");
        let first = claim_scratch(&asked).unwrap();
        let planted = first.path.join("Cargo.toml");
        std::fs::write(&planted, "[package]\nname = \"spintop-snippet-x\"\n").unwrap();
        let second = claim_scratch(&asked).unwrap();
        assert_eq!(first.path, std::fs::canonicalize(&asked).unwrap());
        assert_eq!(second.path, first.path.with_file_name("scratch-2"));
        assert!(
            planted.is_file(),
            "the second server removed the first's project"
        );
        let mode = std::fs::metadata(&second.path)
            .unwrap()
            .permissions()
            .mode();
        assert_eq!(mode & 0o777, 0o700);
        drop(first);
        let third = claim_scratch(&asked).unwrap();
        assert_eq!(third.path, std::fs::canonicalize(&asked).unwrap());
        assert!(!planted.exists(), "not made fresh");
        drop((second, third));
        std::fs::remove_dir_all(&root).unwrap();
    }
}

//! The folders the server trusts are the reader's own: the built book it
//! serves with the token, the scratch project it builds, and no cargo
//! configuration above the scratch folder that the reader did not write.

use super::*;
use spintop_server::ServerError;
use std::os::unix::fs::PermissionsExt;

/// A server's configuration with `site` and `scratch`.
fn config(site: PathBuf, scratch: PathBuf) -> Config {
    super::config(site, scratch, limits(), Containment::Group)
}

/// Why `Server::bind` refused `config`, or a panic if it did not.
fn refusal(config: Config) -> String {
    match Server::bind(config) {
        Err(e @ ServerError::Folder(_)) => e.to_string(),
        Err(e) => panic!("refused for another reason: {e}"),
        Ok(s) => panic!("served {}", s.url()),
    }
}

fn chmod(path: &Path, mode: u32) {
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(mode)).unwrap();
}

/// `--site` and `--scratch` in a folder every user can write (as a shared
/// folder, or /tmp itself) are refused: another user could put an
/// `index.html` there that the book would serve with its token, or a
/// `build.rs` that the build would run as the reader. The same folders,
/// made the reader's alone, are taken; a sticky folder above (as /tmp is)
/// is no reason to refuse.
#[test]
fn site_and_scratch_in_a_folder_others_can_write_are_refused() {
    let root = scratch_root("shared-folder");
    let shared = root.join("shared");
    std::fs::create_dir_all(&shared).unwrap();
    let own_site = site(&root);
    chmod(&shared, 0o777);
    let shared_site = site(&shared);
    let why = refusal(config(shared_site.clone(), root.join("scratch")));
    assert!(
        why.starts_with(&format!("--site {}", shared_site.display())),
        "{why}"
    );
    assert!(
        why.contains("can be written by every user (mode 0777)"),
        "{why}"
    );
    assert!(why.contains("receive the book's token"), "{why}");
    let why = refusal(config(own_site.clone(), shared.join("scratch")));
    assert!(why.starts_with("--scratch "), "{why}");
    assert!(
        why.contains("plant code that the build runs as you"),
        "{why}"
    );
    // The site folder itself writable by a group shared with another user
    // (as root: uid 65534's primary group, which two system users share
    // too), or sticky and open (a sticky bit protects entries, not the
    // creation of index.html).
    let shared_group = can_become_another_user();
    if shared_group {
        std::os::unix::fs::chown(&own_site, None, Some(NOBODY)).unwrap();
    }
    for mode in [0o775, 0o1777] {
        if mode == 0o775 && !shared_group {
            continue;
        }
        chmod(&own_site, mode);
        let why = refusal(config(own_site.clone(), root.join("scratch")));
        assert!(why.contains("can be written by"), "{mode:o}: {why}");
    }
    // Made the reader's alone: taken. The shared folder above is sticky
    // now, as /tmp is.
    chmod(&own_site, 0o755);
    chmod(&shared, 0o1777);
    let s = Server::bind(config(shared_site, shared.join("scratch"))).unwrap();
    drop(s);
    let _ = std::fs::remove_dir_all(&root);
}

/// A folder of another user (uid 65534, when this runs as root) is not the
/// reader's, whatever its mode; `spintop book` says so and exits 2.
#[test]
fn a_site_of_another_user_is_refused_by_spintop_book() {
    if !can_become_another_user() {
        return;
    }
    let root = scratch_root("their-site");
    let theirs = site(&root);
    std::os::unix::fs::chown(&theirs, Some(NOBODY), Some(NOBODY)).unwrap();
    let why = refusal(config(theirs.clone(), root.join("scratch")));
    assert!(why.contains("belongs to uid 65534, not to you"), "{why}");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args(["book", "--site"])
        .arg(&theirs)
        .arg("--scratch")
        .arg(root.join("scratch"))
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{said}");
    assert!(said.contains("belongs to uid 65534"), "{said}");
    assert_eq!(said.lines().count(), 1, "{said}");
    assert!(!root.join("scratch").exists(), "the scratch was touched");
    let _ = std::fs::remove_dir_all(&root);
}

/// The scratch folder is made fresh at each start, readable by the reader
/// only: what an old one held (a planted `build.rs`) is gone. A folder
/// that is not a scratch project of `spintop book` is never emptied.
#[test]
fn the_scratch_folder_is_made_fresh_and_private() {
    use std::os::unix::fs::MetadataExt;
    let root = scratch_root("fresh");
    let scratch = root.join("scratch");
    std::fs::create_dir_all(scratch.join("src")).unwrap();
    std::fs::write(
        scratch.join("Cargo.toml"),
        "[package]\nname = \"spintop-snippet-0badc0de\"\n",
    )
    .unwrap();
    std::fs::write(scratch.join("build.rs"), "fn main() {}").unwrap();
    chmod(&scratch, 0o755);
    let s = Server::bind(config(site(&root), scratch.clone())).unwrap();
    let meta = std::fs::metadata(&scratch).unwrap();
    assert_eq!(meta.mode() & 0o7777, 0o700);
    assert_eq!(std::fs::read_dir(&scratch).unwrap().count(), 0);
    drop(s);
    // Another folder, named by mistake: refused, and left as it was.
    let mine = root.join("notes");
    std::fs::create_dir_all(&mine).unwrap();
    std::fs::write(mine.join("thesis.tex"), "…").unwrap();
    let why = refusal(config(site(&root), mine.clone()));
    assert!(why.contains("is not a scratch project"), "{why}");
    assert!(mine.join("thesis.tex").is_file());
    let _ = std::fs::remove_dir_all(&root);
}

/// Cargo reads `.cargo/config.toml` in the folder it runs in and in every
/// folder above, whoever wrote it: one that another user plants in a
/// sticky folder above the scratch project (as /tmp) could name a
/// `rustc-wrapper` that the build runs as the reader. The server runs cargo
/// in `/` with the project's path, so that no such file is read: the build
/// succeeds and the wrapper never runs. The same file is read when cargo
/// runs in that folder (so the check could fail).
#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_cargo_config_above_the_scratch_folder_is_not_read() {
    let root = scratch_root("cargo-config");
    let planted = root.join(".cargo");
    std::fs::create_dir_all(&planted).unwrap();
    let marker = root.join("the-wrapper-ran");
    let wrapper = root.join("wrapper.sh");
    std::fs::write(
        &wrapper,
        format!("#!/bin/sh\necho ran >> {}\nexec \"$@\"\n", marker.display()),
    )
    .unwrap();
    chmod(&wrapper, 0o755);
    std::fs::write(
        planted.join("config.toml"),
        format!(
            "[build]\nrustc-wrapper = {:?}\n",
            wrapper.display().to_string()
        ),
    )
    .unwrap();
    // The check can fail: cargo in that folder reads the planted file.
    let probe = root.join("probe");
    std::fs::create_dir_all(probe.join("src")).unwrap();
    std::fs::write(
        probe.join("Cargo.toml"),
        "[package]\nname = \"probe\"\nversion = \"0.0.0\"\nedition = \"2021\"\n[workspace]\n",
    )
    .unwrap();
    std::fs::write(probe.join("src/main.rs"), "fn main() {}\n").unwrap();
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let built = std::process::Command::new(&cargo)
        .args(["build", "--quiet"])
        .current_dir(&probe)
        .env("CARGO_TARGET_DIR", root.join("probe-target"))
        .status()
        .unwrap();
    assert!(built.success());
    assert!(
        marker.is_file(),
        "the planted wrapper was not read by cargo in its folder"
    );
    std::fs::remove_file(&marker).unwrap();
    // The server's build, with the scratch project in that folder.
    let s = Server::bind(config(site(&root), root.join("scratch"))).unwrap();
    let (stop, server) = (Arc::new(AtomicBool::new(false)), Arc::new(s));
    let (flag, serving) = (Arc::clone(&stop), Arc::clone(&server));
    let thread = std::thread::spawn(move || serving.serve(&flag));
    let origin = format!("http://127.0.0.1:{}", server.port());
    let (status, text) = request(
        server.port(),
        "POST",
        "/evaluate.json",
        &[("X-Spintop-Token", server.token()), ("Origin", &origin)],
        &body("println!(\"built without the wrapper\");"),
    )
    .unwrap();
    stop.store(true, Ordering::Relaxed);
    thread.join().unwrap();
    assert_eq!(status, 200, "{text}");
    assert!(text.contains("built without the wrapper"), "{text}");
    assert!(!marker.exists(), "the planted rustc-wrapper ran");
    let _ = std::fs::remove_dir_all(&root);
}

/// Two `spintop book` at once with one scratch folder (two in one clone:
/// both take `target/spintop-book/scratch`) each compile in a folder of
/// their own and run their own program: the second takes the folder
/// beside the first's, and neither ever runs the other's snippet, however
/// their ▶ interleave; once the first is killed (SIGKILL), the next
/// server takes its folder. With the stand-in cargo (no compiler), the real
/// servers and supervisors.
#[test]
fn two_servers_at_once_never_run_each_others_snippet() {
    let root = scratch_root("two-servers");
    let site = site(&root);
    let cargo = fake_cargo(&root);
    let target = root.join("target");
    std::fs::create_dir_all(&target).unwrap();
    let scratch = root.join("scratch");
    let options = || BookOptions {
        env: vec![
            ("CARGO".into(), cargo.clone().into()),
            ("CARGO_TARGET_DIR".into(), target.clone().into()),
        ],
        ..BookOptions::default()
    };
    let books = [
        Book::start_with(&site, &scratch, options()),
        Book::start_with(&site, &scratch, options()),
    ];
    // Each says where it is, and which server it is.
    let run = |(port, token): (u16, &str), who: &str| -> String {
        let code = script(&format!("sleep 0.05; echo \"{who} in $(pwd)\""));
        let (status, text) = request(
            port,
            "POST",
            "/evaluate.json",
            &[("X-Spintop-Token", token)],
            &body(&code),
        )
        .unwrap();
        assert_eq!(status, 200, "{text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        v["result"].as_str().unwrap_or("").trim().to_string()
    };
    let mut folders = [Vec::new(), Vec::new()];
    for round in 0..6 {
        let said: Vec<String> = std::thread::scope(|scope| {
            let runs: Vec<_> = books
                .iter()
                .zip(["first", "second"])
                .map(|(book, who)| {
                    let key = (book.port, book.token.as_str());
                    scope.spawn(move || run(key, who))
                })
                .collect();
            runs.into_iter().map(|r| r.join().unwrap()).collect()
        });
        for (i, (said, who)) in said.iter().zip(["first", "second"]).enumerate() {
            assert!(
                said.starts_with(&format!("{who} in ")),
                "round {round}: the {who} server ran {said:?}"
            );
            folders[i].push(said.split(" in ").nth(1).unwrap().to_string());
        }
    }
    let first = std::fs::canonicalize(&scratch).unwrap();
    let second = first.with_file_name("scratch-2");
    assert!(
        folders[0].iter().all(|f| Path::new(f) == first),
        "{folders:?}"
    );
    assert!(
        folders[1].iter().all(|f| Path::new(f) == second),
        "{folders:?}"
    );
    let programs = std::fs::read_dir(target.join("debug"))
        .unwrap()
        .filter(|e| {
            e.as_ref().is_ok_and(|e| {
                e.file_name()
                    .to_string_lossy()
                    .starts_with("spintop-snippet-")
            })
        })
        .count();
    assert_eq!(programs, 2, "one program each");
    // SIGKILL frees the first's folder (the kernel drops its lock): the
    // next server takes it again, while the second still holds its own.
    let mut books = books;
    books[0].stop(rustix::process::Signal::KILL);
    let third = Book::start_with(&site, &scratch, options());
    let said = run((third.port, third.token.as_str()), "third");
    assert_eq!(said, format!("third in {}", first.display()));
    drop((books, third));
    let _ = std::fs::remove_dir_all(&root);
}

/// In a sticky folder others may write (as /tmp), another user (uid 65534,
/// when this runs as root) who puts a file or a link where the scratch
/// folder's lock goes can neither have the server follow the link nor
/// share the lock: refused, saying whose it is, and nothing is made.
#[test]
fn a_lock_file_another_user_planted_beside_the_scratch_is_refused() {
    if !can_become_another_user() {
        return;
    }
    let root = scratch_root("planted-lock");
    let open = root.join("open");
    std::fs::create_dir_all(&open).unwrap();
    chmod(&open, 0o1777);
    let planted = open.join("scratch.lock");
    std::fs::write(&planted, "").unwrap();
    std::os::unix::fs::chown(&planted, Some(NOBODY), Some(NOBODY)).unwrap();
    let why = refusal(config(site(&root), open.join("scratch")));
    assert!(
        why.contains("lock file scratch.lock belongs to uid 65534"),
        "{why}"
    );
    std::fs::remove_file(&planted).unwrap();
    let target = root.join("elsewhere");
    std::os::unix::fs::symlink(&target, &planted).unwrap();
    std::os::unix::fs::lchown(&planted, Some(NOBODY), Some(NOBODY)).unwrap();
    let why = refusal(config(site(&root), open.join("scratch")));
    assert!(why.contains("cannot make its lock file"), "{why}");
    assert!(!target.exists(), "the link was followed");
    assert!(!open.join("scratch").exists());
    let _ = std::fs::remove_dir_all(&root);
}

/// Whether group `gid` has user `uid` as its one member, asked of the
/// system's databases (`getent`, NSS included) independently of the
/// server's reading of `/etc/group` and `/etc/passwd`.
fn private_group(gid: u32, uid: u32) -> bool {
    let sh = |script: String| {
        std::process::Command::new("sh")
            .args(["-c", &script])
            .output()
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
            .unwrap_or_default()
    };
    let primary = sh(format!(
        "getent passwd | awk -F: '$4 == {gid} {{ print $3 }}' | sort -u"
    ));
    let name = sh(format!("getent passwd {uid} | cut -d: -f1"));
    let listed = sh(format!("getent group {gid} | cut -d: -f4"));
    let listed_ok = listed.is_empty() || listed == name;
    let primary_ok = primary.is_empty() || primary == uid.to_string();
    listed_ok && primary_ok && (!primary.is_empty() || !listed.is_empty())
}

/// Debian, Ubuntu and Fedora give each user a private group and a umask of
/// 002, so a clone's folders are writable by their group, which is the
/// reader's alone: `spintop book` serves such a clone's book and builds in
/// its scratch and build folders (as Debian's OpenSSH takes such a home).
#[test]
fn a_clone_made_with_umask_002_in_a_private_group_is_taken() {
    use std::os::unix::fs::MetadataExt;
    let root = scratch_root("umask-002");
    let site = site(&root);
    for folder in [&root, &site, &site.join("css")] {
        chmod(folder, 0o775);
    }
    let meta = std::fs::metadata(&root).unwrap();
    let me = rustix::process::geteuid().as_raw();
    if !private_group(meta.gid(), me) {
        eprintln!("gid {} is not uid {me}'s alone here: skipped", meta.gid());
        let _ = std::fs::remove_dir_all(&root);
        return;
    }
    let server = Server::bind(config(site, root.join("scratch")))
        .unwrap_or_else(|e| panic!("a private group's folder refused: {e}"));
    drop(server);
    let _ = std::fs::remove_dir_all(&root);
}

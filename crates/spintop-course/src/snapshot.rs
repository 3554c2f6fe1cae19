//! The snapshot: a student's `src/**/*.rs` copied once, before anything of
//! it is checked, built or run, into a private folder that nobody else can
//! change, so that the rule, the build and the runner all see the same
//! files (a `src/` swapped for a link to the solutions halfway through a
//! grading changes nothing).
//!
//! It follows no link (each folder and file is opened with `O_NOFOLLOW`
//! below the one before it, so a link swapped in between a check and an
//! open is refused, not followed), reads regular files only (a FIFO, a
//! device, a socket named `.rs` is refused without being opened for
//! reading), and checks each file's size before reading it: a 3 GB sparse
//! file costs a `stat`, not 3 GB of memory. The student's progress file
//! (`target/spintop-course.json`) is read the same way, bounded.

use std::path::{Path, PathBuf};

/// How much a snapshot may hold: a course is a few dozen kB.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// The largest file, in bytes.
    pub file: u64,
    /// All the files together, in bytes.
    pub total: u64,
    /// How many files.
    pub files: usize,
    /// How many folders deep below `src/`.
    pub depth: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            file: 1 << 20,
            total: 4 << 20,
            files: 500,
            depth: 16,
        }
    }
}

/// A file of `src/` that was not copied, and why (a link, not a regular
/// file, too large): the source rule refuses the copy with it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refused {
    /// The file, relative to the copy (`src/…`).
    pub path: PathBuf,
    /// Why.
    pub why: String,
}

/// What a snapshot copied.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Snapshot {
    /// The files copied, relative to the copy (`src/…`), sorted.
    pub files: Vec<PathBuf>,
    /// The entries refused.
    pub refused: Vec<Refused>,
    /// The bytes copied.
    pub bytes: u64,
}

/// Why a copy could not be snapshotted at all.
#[derive(Debug, thiserror::Error)]
pub enum SnapshotError {
    /// `src/` is a link, or not a folder.
    #[error(
        "src/ is a symbolic link or not a folder: the files it stands for are not the copy's own"
    )]
    SrcNotAFolder,
    /// The copy holds more than a course does.
    #[error("src/ holds more than a course does ({0}); nothing of it was graded")]
    TooMuch(String),
    /// A file system error.
    #[error("{path}: {source}")]
    Io {
        /// Where.
        path: PathBuf,
        /// What.
        source: std::io::Error,
    },
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> SnapshotError + '_ {
    move |source| SnapshotError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Copies the `.rs` files under `copy/src` into `into/src` (which must not
/// hold a `src/` yet), within `limits`. Folders are created 0700, files 0600.
pub fn take(copy: &Path, into: &Path, limits: &Limits) -> Result<Snapshot, SnapshotError> {
    imp::take(copy, into, limits)
}

/// Why a bounded read gave nothing.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// No such file.
    #[error("no such file")]
    Missing,
    /// A link, a FIFO, a device: not a regular file.
    #[error("not a regular file (a link, a FIFO or a device)")]
    NotAFile,
    /// Larger than the bound.
    #[error("larger than {0} bytes")]
    TooLarge(u64),
    /// Another error.
    #[error("{0}")]
    Io(std::io::Error),
}

/// The file `rel` (a relative path of plain names) below `dir`, if it is a
/// regular file of at most `cap` bytes, reached without following a link
/// below `dir` and without blocking (a FIFO is refused, not opened for a
/// read that would wait for a writer).
pub fn read_bounded(dir: &Path, rel: &Path, cap: u64) -> Result<Vec<u8>, ReadError> {
    imp::read_bounded(dir, rel, cap)
}

fn is_rust(name: &Path) -> bool {
    name.extension().is_some_and(|x| x == "rs")
}

#[cfg(unix)]
mod imp {
    use super::*;
    use rustix::fs::{self as rfs, AtFlags, FileType, Mode, OFlags};
    use std::ffi::OsStr;
    use std::io::Read;
    use std::os::fd::OwnedFd;
    use std::os::unix::ffi::OsStrExt;
    use std::os::unix::fs::{DirBuilderExt, OpenOptionsExt};

    const DIR: OFlags = OFlags::RDONLY
        .union(OFlags::DIRECTORY)
        .union(OFlags::NOFOLLOW)
        .union(OFlags::CLOEXEC);
    const FILE: OFlags = OFlags::RDONLY
        .union(OFlags::NOFOLLOW)
        .union(OFlags::NONBLOCK)
        .union(OFlags::CLOEXEC);

    fn open_dir(path: &Path) -> std::io::Result<OwnedFd> {
        // The folder given (a student's copy) may itself be reached by a
        // link the instructor chose; below it, nothing is followed.
        Ok(rfs::open(
            path,
            OFlags::RDONLY | OFlags::DIRECTORY | OFlags::CLOEXEC,
            Mode::empty(),
        )?)
    }

    /// Reads the open regular file `fd` of `size` bytes (refusing one that
    /// grew meanwhile).
    fn read_all(fd: OwnedFd, size: u64) -> std::io::Result<Vec<u8>> {
        let mut bytes = Vec::with_capacity(size as usize);
        std::fs::File::from(fd)
            .take(size + 1)
            .read_to_end(&mut bytes)?;
        if bytes.len() as u64 > size {
            return Err(std::io::Error::other("the file grew while it was read"));
        }
        Ok(bytes)
    }

    /// Opens `name` in `dir` as a regular file of at most `cap` bytes.
    fn open_file(dir: &OwnedFd, name: &OsStr, cap: u64) -> Result<(OwnedFd, u64), ReadError> {
        let fd = match rfs::openat(dir, name, FILE, Mode::empty()) {
            Ok(fd) => fd,
            Err(rustix::io::Errno::NOENT) => return Err(ReadError::Missing),
            Err(rustix::io::Errno::LOOP) => return Err(ReadError::NotAFile),
            Err(e) => return Err(ReadError::Io(e.into())),
        };
        let stat = rfs::fstat(&fd).map_err(|e| ReadError::Io(e.into()))?;
        if FileType::from_raw_mode(stat.st_mode) != FileType::RegularFile {
            return Err(ReadError::NotAFile);
        }
        let size = stat.st_size.max(0) as u64;
        if size > cap {
            return Err(ReadError::TooLarge(cap));
        }
        Ok((fd, size))
    }

    pub(super) fn read_bounded(dir: &Path, rel: &Path, cap: u64) -> Result<Vec<u8>, ReadError> {
        let mut fd = open_dir(dir).map_err(|e| match e.kind() {
            std::io::ErrorKind::NotFound => ReadError::Missing,
            _ => ReadError::Io(e),
        })?;
        let names: Vec<&OsStr> = rel.iter().collect();
        let Some((file, folders)) = names.split_last() else {
            return Err(ReadError::Missing);
        };
        for name in folders {
            fd = match rfs::openat(&fd, *name, DIR, Mode::empty()) {
                Ok(fd) => fd,
                Err(rustix::io::Errno::NOENT) => return Err(ReadError::Missing),
                Err(rustix::io::Errno::LOOP | rustix::io::Errno::NOTDIR) => {
                    return Err(ReadError::NotAFile);
                }
                Err(e) => return Err(ReadError::Io(e.into())),
            };
        }
        let (fd, size) = open_file(&fd, file, cap)?;
        read_all(fd, size).map_err(ReadError::Io)
    }

    /// The walk's state.
    struct Walk<'a> {
        into: &'a Path,
        limits: &'a Limits,
        out: Snapshot,
    }

    pub(super) fn take(
        copy: &Path,
        into: &Path,
        limits: &Limits,
    ) -> Result<Snapshot, SnapshotError> {
        let top = open_dir(copy).map_err(io(copy))?;
        let src = match rfs::openat(&top, "src", DIR, Mode::empty()) {
            Ok(fd) => fd,
            Err(rustix::io::Errno::LOOP | rustix::io::Errno::NOTDIR | rustix::io::Errno::NOENT) => {
                return Err(SnapshotError::SrcNotAFolder);
            }
            Err(e) => return Err(io(&copy.join("src"))(e.into())),
        };
        let mut walk = Walk {
            into,
            limits,
            out: Snapshot::default(),
        };
        walk.folder(&src, Path::new("src"), 0)?;
        walk.out.files.sort();
        Ok(walk.out)
    }

    impl Walk<'_> {
        fn make_dir(&self, rel: &Path) -> Result<(), SnapshotError> {
            let path = self.into.join(rel);
            std::fs::DirBuilder::new()
                .recursive(true)
                .mode(0o700)
                .create(&path)
                .map_err(io(&path))
        }

        fn refuse(&mut self, rel: PathBuf, why: impl Into<String>) {
            self.out.refused.push(Refused {
                path: rel,
                why: why.into(),
            });
        }

        fn folder(&mut self, fd: &OwnedFd, rel: &Path, depth: usize) -> Result<(), SnapshotError> {
            if depth > self.limits.depth {
                return Err(SnapshotError::TooMuch(format!(
                    "folders more than {} deep",
                    self.limits.depth
                )));
            }
            self.make_dir(rel)?;
            let mut names = Vec::new();
            for entry in rfs::Dir::read_from(fd).map_err(|e| io(rel)(e.into()))? {
                let entry = entry.map_err(|e| io(rel)(e.into()))?;
                let name = OsStr::from_bytes(entry.file_name().to_bytes()).to_os_string();
                if name != "." && name != ".." {
                    names.push(name);
                }
                if names.len() > 4 * self.limits.files {
                    return Err(SnapshotError::TooMuch(format!(
                        "more than {} entries in {}",
                        4 * self.limits.files,
                        rel.display()
                    )));
                }
            }
            names.sort();
            for name in names {
                self.entry(fd, rel, &name, depth)?;
            }
            Ok(())
        }

        fn entry(
            &mut self,
            dir: &OwnedFd,
            rel: &Path,
            name: &OsStr,
            depth: usize,
        ) -> Result<(), SnapshotError> {
            let here = rel.join(name);
            let stat = rfs::statat(dir, name, AtFlags::SYMLINK_NOFOLLOW)
                .map_err(|e| io(&here)(e.into()))?;
            match FileType::from_raw_mode(stat.st_mode) {
                FileType::Directory => match rfs::openat(dir, name, DIR, Mode::empty()) {
                    Ok(fd) => self.folder(&fd, &here, depth + 1),
                    // Swapped for a link between the look and the open.
                    Err(_) => {
                        self.refuse(here, "a folder that changed into a link while it was read");
                        Ok(())
                    }
                },
                FileType::Symlink => {
                    self.refuse(
                        here,
                        "a symbolic link: the compiler would read the file it stands for, wherever that is; put the file itself here",
                    );
                    Ok(())
                }
                _ if !is_rust(Path::new(name)) => Ok(()),
                FileType::RegularFile => self.file(dir, here, name),
                _ => {
                    self.refuse(here, "not a regular file (a FIFO, a socket or a device)");
                    Ok(())
                }
            }
        }

        fn file(
            &mut self,
            dir: &OwnedFd,
            here: PathBuf,
            name: &OsStr,
        ) -> Result<(), SnapshotError> {
            let (fd, size) = match open_file(dir, name, self.limits.file) {
                Ok(f) => f,
                Err(ReadError::TooLarge(cap)) => {
                    self.refuse(
                        here,
                        format!("larger than {} kB, far beyond any assignment", cap >> 10),
                    );
                    return Ok(());
                }
                Err(ReadError::NotAFile | ReadError::Missing) => {
                    self.refuse(
                        here,
                        "changed into a link or a special file while it was read",
                    );
                    return Ok(());
                }
                Err(ReadError::Io(e)) => return Err(io(&here)(e)),
            };
            if self.out.files.len() >= self.limits.files {
                return Err(SnapshotError::TooMuch(format!(
                    "more than {} files",
                    self.limits.files
                )));
            }
            if self.out.bytes + size > self.limits.total {
                return Err(SnapshotError::TooMuch(format!(
                    "more than {} MB of Rust files",
                    self.limits.total >> 20
                )));
            }
            let bytes = read_all(fd, size).map_err(io(&here))?;
            let to = self.into.join(&here);
            let mut file = std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .mode(0o600)
                .open(&to)
                .map_err(io(&to))?;
            std::io::Write::write_all(&mut file, &bytes).map_err(io(&to))?;
            self.out.bytes += bytes.len() as u64;
            self.out.files.push(here);
            Ok(())
        }
    }
}

#[cfg(not(unix))]
mod imp {
    //! Without `openat` and `O_NOFOLLOW`: each entry is looked at
    //! (`symlink_metadata`) before it is opened, which leaves a moment in
    //! between (lessons/README.md says what that allows).
    use super::*;

    pub(super) fn read_bounded(dir: &Path, rel: &Path, cap: u64) -> Result<Vec<u8>, ReadError> {
        let mut path = dir.to_path_buf();
        for name in rel.iter() {
            path.push(name);
            let meta = std::fs::symlink_metadata(&path).map_err(|e| match e.kind() {
                std::io::ErrorKind::NotFound => ReadError::Missing,
                _ => ReadError::Io(e),
            })?;
            if meta.file_type().is_symlink() {
                return Err(ReadError::NotAFile);
            }
        }
        let meta = std::fs::symlink_metadata(&path).map_err(ReadError::Io)?;
        if !meta.is_file() {
            return Err(ReadError::NotAFile);
        }
        if meta.len() > cap {
            return Err(ReadError::TooLarge(cap));
        }
        std::fs::read(&path).map_err(ReadError::Io)
    }

    pub(super) fn take(
        copy: &Path,
        into: &Path,
        limits: &Limits,
    ) -> Result<Snapshot, SnapshotError> {
        let src = copy.join("src");
        if !std::fs::symlink_metadata(&src).is_ok_and(|m| m.is_dir()) {
            return Err(SnapshotError::SrcNotAFolder);
        }
        let mut out = Snapshot::default();
        let mut stack = vec![(PathBuf::from("src"), 0)];
        while let Some((rel, depth)) = stack.pop() {
            if depth > limits.depth {
                return Err(SnapshotError::TooMuch(format!(
                    "folders more than {} deep",
                    limits.depth
                )));
            }
            std::fs::create_dir_all(into.join(&rel)).map_err(io(&rel))?;
            for entry in std::fs::read_dir(copy.join(&rel)).map_err(io(&rel))? {
                let entry = entry.map_err(io(&rel))?;
                let here = rel.join(entry.file_name());
                let meta = std::fs::symlink_metadata(copy.join(&here)).map_err(io(&here))?;
                if meta.file_type().is_symlink() {
                    out.refused.push(Refused {
                        path: here,
                        why: "a symbolic link".into(),
                    });
                } else if meta.is_dir() {
                    stack.push((here, depth + 1));
                } else if is_rust(&here) {
                    match read_bounded(copy, &here, limits.file) {
                        Ok(bytes) => {
                            out.bytes += bytes.len() as u64;
                            if out.bytes > limits.total || out.files.len() >= limits.files {
                                return Err(SnapshotError::TooMuch("more than a course".into()));
                            }
                            std::fs::write(into.join(&here), &bytes).map_err(io(&here))?;
                            out.files.push(here);
                        }
                        Err(e) => out.refused.push(Refused {
                            path: here,
                            why: e.to_string(),
                        }),
                    }
                }
            }
        }
        out.files.sort();
        Ok(out)
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use std::time::{Duration, Instant};

    fn fresh(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("spintop-snap-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("src/nested/deeper")).unwrap();
        dir
    }

    fn mkfifo(path: &Path) {
        rustix::fs::mknodat(
            rustix::fs::CWD,
            path,
            rustix::fs::FileType::Fifo,
            rustix::fs::Mode::from_raw_mode(0o600),
            0,
        )
        .unwrap();
    }

    #[test]
    fn a_snapshot_copies_rust_files_and_refuses_links_fifos_and_giants_without_reading_them() {
        let copy = fresh("copy");
        std::fs::write(copy.join("src/lib.rs"), "mod nested;\n").unwrap();
        std::fs::write(copy.join("src/nested/deeper/x.rs"), "pub fn x() {}\n").unwrap();
        std::fs::write(copy.join("src/notes.txt"), "not rust\n").unwrap();
        std::os::unix::fs::symlink("/etc/passwd", copy.join("src/link.rs")).unwrap();
        mkfifo(&copy.join("src/pipe.rs"));
        // 3 GB, sparse: a stat, never a read.
        let giant = std::fs::File::create(copy.join("src/giant.rs")).unwrap();
        giant.set_len(3 << 30).unwrap();
        let into = copy.join("snapshot");
        let start = Instant::now();
        let snap = take(&copy, &into, &Limits::default()).unwrap();
        assert!(start.elapsed() < Duration::from_secs(5));
        assert_eq!(
            snap.files,
            [
                PathBuf::from("src/lib.rs"),
                PathBuf::from("src/nested/deeper/x.rs")
            ]
        );
        let refused: Vec<String> = snap
            .refused
            .iter()
            .map(|r| r.path.display().to_string())
            .collect();
        assert_eq!(
            refused,
            ["src/giant.rs", "src/link.rs", "src/pipe.rs"],
            "{snap:?}"
        );
        assert!(snap.refused[0].why.contains("larger than"));
        assert!(snap.refused[1].why.contains("symbolic link"));
        assert!(snap.refused[2].why.contains("not a regular file"));
        assert!(!into.join("src/notes.txt").exists());
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(into.join("src/nested"))
            .unwrap()
            .permissions()
            .mode();
        assert_eq!(mode & 0o777, 0o700);
        std::fs::remove_dir_all(&copy).unwrap();
    }

    #[test]
    fn a_src_that_is_a_link_is_not_walked() {
        let copy = fresh("src-link");
        std::fs::remove_dir_all(copy.join("src")).unwrap();
        std::os::unix::fs::symlink("/etc", copy.join("src")).unwrap();
        let err = take(&copy, &copy.join("snapshot"), &Limits::default()).unwrap_err();
        assert!(matches!(err, SnapshotError::SrcNotAFolder), "{err}");
        std::fs::remove_dir_all(&copy).unwrap();
    }

    #[test]
    fn a_bounded_read_refuses_a_fifo_a_device_and_a_link_at_once() {
        let dir = fresh("bounded");
        std::fs::create_dir_all(dir.join("target")).unwrap();
        mkfifo(&dir.join("target/fifo.json"));
        std::os::unix::fs::symlink("/dev/zero", dir.join("target/zero.json")).unwrap();
        std::os::unix::fs::symlink("/etc", dir.join("linked")).unwrap();
        std::fs::write(dir.join("target/big.json"), vec![b' '; 2000]).unwrap();
        std::fs::write(dir.join("target/ok.json"), b"{}").unwrap();
        let start = Instant::now();
        let read = |rel: &str| read_bounded(&dir, Path::new(rel), 1000);
        assert!(matches!(read("target/fifo.json"), Err(ReadError::NotAFile)));
        assert!(matches!(read("target/zero.json"), Err(ReadError::NotAFile)));
        assert!(matches!(read("linked/passwd"), Err(ReadError::NotAFile)));
        assert!(matches!(
            read("target/big.json"),
            Err(ReadError::TooLarge(1000))
        ));
        assert!(matches!(read("target/none.json"), Err(ReadError::Missing)));
        assert_eq!(read("target/ok.json").unwrap(), b"{}");
        assert!(start.elapsed() < Duration::from_secs(2), "nothing waited");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

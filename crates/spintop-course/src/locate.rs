//! Which course a command stands in, and how its files and commands are
//! named there.
//!
//! The one rule, as cargo finds its manifest: the course is the folder the
//! command is run in or the nearest of its parents that is one: a lessons
//! crate (a `Cargo.toml` naming the package `spintop-lessons…`, with `src/`
//! and `tests/`), or a clone of the repository (its `lessons/` is the
//! course). `spintop course` and `spintop learn` both ask here; where none
//! is found they grade the repository this spintop was built from, and say
//! so.
//!
//! A student's copy names its files from its own top (`src/ch2.rs`, `cargo
//! test --test ch2`); the repository's lessons from the repository's top
//! (`lessons/src/ch2.rs`, `cargo test -p spintop-lessons --test ch2`).

use super::{Assignment, lessons_dir, repository};
use std::path::{Path, PathBuf};

/// The package name of the repository's lessons; a copy's is this, a dash
/// and a key (`spintop-lessons-0a1b2c3d`).
const PACKAGE: &str = "spintop-lessons";

/// Whether `dir` is a lessons crate: its manifest names a `spintop-lessons`
/// package, and it has the stubs (`src/`) and the graders (`tests/`).
pub fn is_course(dir: &Path) -> bool {
    if !dir.join("src").is_dir() || !dir.join("tests").is_dir() {
        return false;
    }
    let Ok(text) = std::fs::read_to_string(dir.join("Cargo.toml")) else {
        return false;
    };
    let Ok(manifest) = text.parse::<toml::Table>() else {
        return false;
    };
    manifest
        .get("package")
        .and_then(|p| p.get("name"))
        .and_then(|n| n.as_str())
        .is_some_and(|n| n == PACKAGE || n.starts_with(&format!("{PACKAGE}-")))
}

/// The course that `start` stands in: `start` or the nearest of its parents
/// that is a lessons crate, or a clone of the repository (whose `lessons/`
/// is then the course). `None` when there is none up to the root.
pub fn find_course(start: &Path) -> Option<PathBuf> {
    let start = std::path::absolute(start).unwrap_or_else(|_| start.to_path_buf());
    start.ancestors().find_map(|dir| {
        if is_course(dir) {
            Some(dir.to_path_buf())
        } else {
            let lessons = lessons_dir(dir);
            is_course(&lessons).then_some(lessons)
        }
    })
}

/// How a course was chosen: named, found where the command stands, or the
/// repository's by default.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Chosen {
    /// Named on the command line (`--course DIR`).
    Named,
    /// Found in the current folder or one of its parents.
    Found,
    /// None was found there: the repository this spintop was built from.
    Default,
}

/// A course as a command names it: where it is, how it was chosen, and how
/// its files and its cargo commands read from its top.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Course {
    /// The lessons crate.
    pub dir: PathBuf,
    /// How it was chosen.
    pub chosen: Chosen,
    /// True for the repository's own `lessons/` (a member of the
    /// repository's workspace), false for a student's copy.
    pub in_repository: bool,
}

impl Course {
    /// The course in `dir`, chosen as `chosen`.
    pub fn at(dir: &Path, chosen: Chosen) -> Self {
        let dir = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
        let in_repository = dir.file_name().is_some_and(|n| n == "lessons")
            && dir.parent().is_some_and(|p| {
                std::fs::read_to_string(p.join("Cargo.toml"))
                    .is_ok_and(|t| t.contains("[workspace]") && t.contains("\"lessons\""))
            });
        Self {
            dir,
            chosen,
            in_repository,
        }
    }

    /// The course a command run in `cwd` grades: `named` if given (relative
    /// to `cwd`), else the one `cwd` stands in, else the repository's.
    pub fn choose(named: Option<&Path>, cwd: &Path) -> Self {
        match named {
            Some(dir) => Self::at(&cwd.join(dir), Chosen::Named),
            None => match find_course(cwd) {
                Some(dir) => Self::at(&dir, Chosen::Found),
                None => Self::at(&lessons_dir(repository()), Chosen::Default),
            },
        }
    }

    /// The folder a student stands in to work on it: the repository's top
    /// for its own lessons, the copy itself otherwise.
    pub fn top(&self) -> &Path {
        if self.in_repository {
            self.dir.parent().unwrap_or(&self.dir)
        } else {
            &self.dir
        }
    }

    /// `file` (a path under the course, such as `src/ch2.rs`) as named from
    /// the course's top: `lessons/src/ch2.rs` in the repository.
    pub fn path(&self, file: &str) -> String {
        if self.in_repository {
            format!("lessons/{file}")
        } else {
            file.to_string()
        }
    }

    /// The file an assignment is in, as named from the course's top.
    pub fn file(&self, a: &Assignment) -> String {
        self.path(a.file.trim_start_matches("lessons/"))
    }

    /// The cargo command that runs one assignment's grader from the course's
    /// top.
    pub fn test_command(&self, a: &Assignment) -> String {
        let package = if self.in_repository {
            format!(" -p {PACKAGE}")
        } else {
            String::new()
        };
        format!("cargo test{package} --test {} {}", a.binary, a.test)
    }

    /// The cargo command that grades the whole course from its top.
    pub fn grade_command(&self) -> String {
        if self.in_repository {
            format!("cargo test -p {PACKAGE}")
        } else {
            "cargo test".to_string()
        }
    }

    /// Which course this is, in words: "your copy at /home/me/course" or
    /// "the repository's lessons at /…/spintop/lessons", and how it was
    /// found when it was not named.
    pub fn describe(&self) -> String {
        let what = if self.in_repository {
            "the repository's lessons"
        } else {
            "the copy"
        };
        let how = match self.chosen {
            Chosen::Named => "",
            Chosen::Found => " (found from the current folder)",
            Chosen::Default => " (no course in the current folder or its parents)",
        };
        format!("{what} at {}{how}", self.dir.display())
    }

    /// The `--course DIR` a printed command must repeat to reach this course
    /// from where the command was run: none when the course was found there
    /// or is the default.
    pub fn course_arg(&self) -> Option<String> {
        (self.chosen == Chosen::Named).then(|| self.dir.display().to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_repository_is_found_from_anywhere_inside_it() {
        let repo = repository();
        let lessons = lessons_dir(repo).canonicalize().unwrap();
        for start in [
            repo.to_path_buf(),
            repo.join("lessons"),
            repo.join("lessons/src"),
            repo.join("crates/spintop/src"),
        ] {
            let found = find_course(&start)
                .expect("a course")
                .canonicalize()
                .unwrap();
            assert_eq!(found, lessons, "from {}", start.display());
        }
        let course = Course::choose(None, &repo.join("crates"));
        assert!(course.in_repository);
        assert_eq!(course.chosen, Chosen::Found);
        let a = &crate::COURSE[0];
        assert_eq!(course.file(a), a.file);
        assert!(
            course
                .test_command(a)
                .starts_with("cargo test -p spintop-lessons --test ")
        );
        assert_eq!(course.course_arg(), None);
    }

    #[test]
    fn a_copy_is_found_from_its_folders_and_named_from_its_top() {
        let copy = std::env::temp_dir().join(format!("spintop-locate-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&copy);
        crate::export(repository(), &copy).unwrap();
        // Its carried crates are not courses; the copy around them is.
        for start in [
            copy.clone(),
            copy.join("src"),
            copy.join("crates/spintop/src"),
        ] {
            let found = find_course(&start).expect("a course");
            assert_eq!(found.canonicalize().unwrap(), copy.canonicalize().unwrap());
        }
        let course = Course::choose(None, &copy.join("tests"));
        assert!(!course.in_repository);
        let a = &crate::COURSE[0];
        assert_eq!(course.file(a), a.file.trim_start_matches("lessons/"));
        assert!(course.test_command(a).starts_with("cargo test --test "));
        assert!(course.describe().starts_with("the copy at "));
        let _ = std::fs::remove_dir_all(&copy);
    }

    #[test]
    fn no_course_is_found_outside_one() {
        assert_eq!(find_course(Path::new("/proc/self")), None);
        let course = Course::choose(None, Path::new("/proc/self"));
        assert_eq!(course.chosen, Chosen::Default);
        assert!(
            course
                .describe()
                .contains("no course in the current folder")
        );
    }
}

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

/// Where the book of a course is: the sources mdBook builds (`book/src`,
/// with `SUMMARY.md`), as `spintop learn` reads them.
const BOOK: &str = "book/src";

/// The book a command reads beside a course, and whose it is.
///
/// The one rule: the book the course carries (a copy made by `spintop course
/// export` holds it in `book/src`, and a clone of the repository in its own
/// `book/src`), else the book of the repository this spintop was built
/// from. What a reader leaves (`spintop learn`'s progress) is kept in the
/// `target/` of [`Book::home`]: the course's own folder whenever a course
/// was found or named (even one that carries no book), the repository's
/// only when none was.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Book {
    /// The book's sources: the folder holding `SUMMARY.md`.
    pub src: PathBuf,
    /// The folder whose `target/` keeps the reader's state: the course's
    /// top (a copy's, a clone's) when a course was found or named, even
    /// when the book read is the repository's; the repository's when none
    /// was.
    pub home: PathBuf,
    /// The course it was looked for in, when that course carries none and
    /// the repository's book is read instead (a copy exported by a spintop
    /// that did not carry the book).
    pub instead_of: Option<PathBuf>,
}

/// No book to read: neither the course nor the repository holds one.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "{looked}, and the repository this spintop was built from has none ({repository} is missing)"
)]
pub struct NoBook {
    /// Where the book was looked for first, in words.
    looked: String,
    /// The repository's `SUMMARY.md`.
    repository: String,
}

impl Book {
    /// The book read beside `course` (see [`Book`]); `repository` is where
    /// spintop was built ([`repository`] outside the tests).
    pub fn beside(course: &Course, repository: &Path) -> Result<Self, NoBook> {
        let top = without_dots(course.top());
        let own = top.join(BOOK);
        if own.join("SUMMARY.md").is_file() {
            return Ok(Self {
                src: own,
                home: top,
                instead_of: None,
            });
        }
        let repository = without_dots(repository);
        let theirs = repository.join(BOOK);
        let found = course.chosen != Chosen::Default;
        if theirs.join("SUMMARY.md").is_file() {
            // The repository's book, but the reader's state stays the
            // course's own: a copy never reads or writes the repository's.
            return Ok(Self {
                src: theirs,
                home: if found { top } else { repository },
                instead_of: found.then(|| course.dir.clone()),
            });
        }
        let looked = if found {
            format!(
                "the course at {} carries no book (no {}; a copy exported by this spintop does)",
                top.display(),
                own.join("SUMMARY.md").display()
            )
        } else {
            "there is no course in the current folder or its parents".to_string()
        };
        Err(NoBook {
            looked,
            repository: theirs.join("SUMMARY.md").display().to_string(),
        })
    }

    /// Which book this is, in words: "the book of the copy at /home/me/course"
    /// or "the repository's book at /…/spintop/book/src", and why the
    /// repository's when a course was found without one.
    pub fn describe(&self) -> String {
        match &self.instead_of {
            None => format!("the book at {}", self.src.display()),
            Some(course) => format!(
                "the repository's book at {} (the course at {} carries none: export it again to carry it)",
                self.src.display(),
                course.display()
            ),
        }
    }
}

/// `path` named without `..` (a `--course ../copy`): resolved if it has one
/// and exists, else as given.
fn without_dots(path: &Path) -> PathBuf {
    let dots = path
        .components()
        .any(|c| c == std::path::Component::ParentDir);
    match path.canonicalize() {
        Ok(resolved) if dots => resolved,
        _ => path.to_path_buf(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// From a folder outside any course the course (the repository's
    /// lessons) is named as the folder it is: no `..` in what is shown.
    #[test]
    fn the_repositorys_lessons_are_named_without_dots() {
        let outside = std::env::temp_dir();
        let course = Course::choose(None, &outside);
        let shown = course.describe();
        assert!(!shown.contains("/.."), "{shown}");
        let real = repository().canonicalize().unwrap().join("lessons");
        assert!(shown.contains(&real.display().to_string()), "{shown}");
    }

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

    /// A folder of its own under the system's temporary folder, made empty.
    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("spintop-book-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// A lessons crate at `dir` as a copy holds it, with a book if asked.
    fn fake_copy(dir: &Path, with_book: bool) {
        for sub in ["src", "tests"] {
            std::fs::create_dir_all(dir.join(sub)).unwrap();
        }
        std::fs::write(
            dir.join("Cargo.toml"),
            "[package]\nname = \"spintop-lessons-0000abcd\"\n",
        )
        .unwrap();
        if with_book {
            fake_book(dir);
        }
    }

    fn fake_book(top: &Path) {
        std::fs::create_dir_all(top.join(BOOK)).unwrap();
        std::fs::write(top.join(BOOK).join("SUMMARY.md"), "- [One](one.md)\n").unwrap();
    }

    #[test]
    fn a_copy_that_carries_the_book_is_read_from_its_own_book() {
        let root = scratch("own");
        let (copy, repo) = (root.join("copy"), root.join("repo"));
        fake_copy(&copy, true);
        fake_book(&repo);
        for course in [
            Course::choose(None, &copy.join("src")),
            Course::choose(Some(&copy), &repo),
        ] {
            assert!(!course.in_repository);
            let book = Book::beside(&course, &repo).unwrap();
            assert_eq!(book.src, copy.join("book/src"));
            assert_eq!(book.home, copy);
            assert_eq!(book.instead_of, None);
            assert!(
                !book.describe().contains(&repo.display().to_string()),
                "{}",
                book.describe()
            );
        }
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_copy_without_a_book_reads_the_repositorys_and_says_why() {
        let root = scratch("older");
        let (copy, repo) = (root.join("copy"), root.join("repo"));
        fake_copy(&copy, false);
        fake_book(&repo);
        let course = Course::choose(None, &copy);
        assert_eq!(course.chosen, Chosen::Found);
        let book = Book::beside(&course, &repo).unwrap();
        assert_eq!(book.src, repo.join("book/src"));
        // The copy's own state, never the repository's.
        assert_eq!(book.home, copy);
        assert_eq!(book.instead_of.as_deref(), Some(copy.as_path()));
        let said = book.describe();
        assert!(
            said.contains(&copy.display().to_string()) && said.contains("carries none"),
            "{said}"
        );
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn the_repositorys_lessons_read_the_book_of_the_clone_they_are_in() {
        // Even where spintop was built is elsewhere (a clone it was not built
        // from): the clone one stands in is the book's home.
        let root = scratch("clone");
        let course = Course::choose(None, &repository().join("lessons/src"));
        assert!(course.in_repository);
        let book = Book::beside(&course, &root.join("gone")).unwrap();
        let top = repository().canonicalize().unwrap();
        assert_eq!(book.src.canonicalize().unwrap(), top.join("book/src"));
        assert_eq!(book.home.canonicalize().unwrap(), top);
        assert_eq!(book.instead_of, None);
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn no_book_anywhere_is_one_line_that_names_where_it_looked() {
        let root = scratch("none");
        let (copy, repo) = (root.join("copy"), root.join("gone"));
        fake_copy(&copy, false);
        let found = Course::choose(None, &copy.join("tests"));
        let defaulted = Course::at(&repo.join("lessons"), Chosen::Default);
        for (course, names) in [(found, Some(&copy)), (defaulted, None)] {
            let e = Book::beside(&course, &repo).unwrap_err().to_string();
            assert!(!e.contains('\n'), "{e}");
            assert!(
                e.contains(&repo.join("book/src/SUMMARY.md").display().to_string()),
                "{e}"
            );
            match names {
                Some(copy) => assert!(e.contains(&copy.display().to_string()), "{e}"),
                None => assert!(e.contains("no course in the current folder"), "{e}"),
            }
        }
        std::fs::remove_dir_all(&root).unwrap();
    }
}

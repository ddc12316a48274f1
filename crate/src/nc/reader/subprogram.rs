//! Subprograms: a main program calling children, as the Fanuc-style controls (`M98 P… L…`,
//! `M99` returns; Moore and Precitech style) and LinuxCNC (`o<name> call [args]`,
//! `o<name> sub` … `o<name> endsub`, `o<name> return`) write them.
//!
//! Where a called program is found:
//! - `M98 P n`: the caller's resolver first ([`ProgramRef::Number`]: a file beside the main
//!   program, or a text the page holds); then a line `O n` in the calling file (Fanuc: several
//!   programs in one file, as LinuxCNC 2.9 also reads). `L` repeats the call (1 without; `L0`
//!   calls nothing). P is the program number as written: Fanuc's packed form with the count in
//!   its leading digits is not decoded.
//! - `o<name> call`: a `o<name> sub` already passed or further on in the calling file; then the
//!   resolver ([`ProgramRef::Name`]: LinuxCNC's file-per-subroutine convention, `name.ngc` on
//!   its subroutine path), whose text must define `o<name> sub` (as rs274 requires).
//!
//! Calls nest at most `max_call_depth` deep ([`super::MAX_CALL_DEPTH`]); the call stack is a
//! vector, not Rust recursion. [`files_beside`] is the resolver for files on disk,
//! [`texts_beside`] the same for texts held in memory (the page's files).

use super::error::Problem;
use super::interpreter::{EventKind, Frame, FrameKind, Mark, OpenFile, Reader, Scan};
use super::lexer::{Head, Label, OKeyword};
use super::source::{Source, StreamSource, TextSource};
use std::path::Path;
use std::sync::Arc;

/// A called program as the program names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgramRef<'r> {
    /// `M98 P1001`: 1001.
    Number(u64),
    /// `o<pass> call`: `pass` (lower case).
    Name(&'r str),
}

/// A program's name (for messages and [`super::Location`]) and its text. The name stands for
/// the text: the reader caches jump targets by it, so two programs given one name must be one
/// text.
pub struct Program<'a> {
    /// The file name or any label the caller chooses.
    pub name: Arc<str>,
    /// The text.
    pub source: Box<dyn Source + 'a>,
}

impl<'a> Program<'a> {
    /// A program held in memory.
    pub fn from_text(name: &str, text: impl AsRef<[u8]> + 'a) -> Self {
        Self {
            name: name.into(),
            source: Box::new(TextSource::new(text)),
        }
    }

    /// A program streamed from a file on disk.
    pub fn open(path: &Path) -> std::io::Result<Program<'static>> {
        let file = std::fs::File::open(path)?;
        Ok(Program {
            name: path.display().to_string().into(),
            source: Box::new(StreamSource::new(file)),
        })
    }
}

impl std::fmt::Debug for Program<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Program({})", self.name)
    }
}

/// Finds a called program: `Ok(None)` when there is none by that name, `Err` with a message
/// when looking failed.
pub type Resolver<'a> = dyn FnMut(ProgramRef<'_>) -> Result<Option<Program<'a>>, String> + 'a;

/// The resolver for files beside `main` (a program's path), by the names [`called_names`]
/// gives. The directory is listed at each call and names are matched exactly, so a
/// case-insensitive file system does not make `O1001.nc` and `o1001.nc` two files.
pub fn files_beside(
    main: &Path,
) -> impl FnMut(ProgramRef<'_>) -> Result<Option<Program<'static>>, String> + use<> {
    let dir = main.parent().map(Path::to_path_buf).unwrap_or_default();
    let stem = stem_of(&main.to_string_lossy());
    move |r: ProgramRef<'_>| {
        let listed = if dir.as_os_str().is_empty() {
            std::fs::read_dir(".")
        } else {
            std::fs::read_dir(&dir)
        };
        let entries = listed.map_err(|e| format!("{}: {e}", dir.display()))?;
        let names: Vec<String> = entries
            .filter_map(|e| e.ok())
            .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        let Some(name) = pick(r, &stem, names.iter().map(String::as_str))? else {
            return Ok(None);
        };
        let path = dir.join(name);
        Program::open(&path)
            .map(Some)
            .map_err(|e| format!("{}: {e}", path.display()))
    }
}

/// The resolver over texts the caller holds (the page's uploaded files), named as on disk:
/// the same names as [`files_beside`], `main` being the main program's file name.
pub fn texts_beside<'a>(
    main: &str,
    files: &'a [(String, String)],
) -> impl FnMut(ProgramRef<'_>) -> Result<Option<Program<'a>>, String> + 'a {
    let stem = stem_of(main);
    move |r: ProgramRef<'_>| {
        let names = files.iter().map(|(n, _)| n.as_str());
        Ok(pick(r, &stem, names)?.and_then(|name| {
            files
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(n, t)| Program::from_text(n, t.as_str()))
        }))
    }
}

/// The file names a call may be written in, in order: for `M98 P n`, `O{n:04}`, `O{n}`, their
/// lower case, `{n:04}`, `{n}` and `{stem}-{n}` (the main file's stem), each bare or with
/// `.nc`, `.NC`, `.ngc`, `.NGC`; for `o<name> call`, `name.ngc`, `name.nc`, `name`.
pub fn called_names(r: ProgramRef<'_>, stem: &str) -> Vec<String> {
    candidates(r, stem)
}

/// The one name among `names` the call may be written in; two are an error (which one the
/// controller takes is not known).
fn pick<'n>(
    r: ProgramRef<'_>,
    stem: &str,
    names: impl Iterator<Item = &'n str>,
) -> Result<Option<&'n str>, String> {
    let wanted = candidates(r, stem);
    let found: Vec<&str> = names.filter(|n| wanted.iter().any(|w| w == n)).collect();
    match found.as_slice() {
        [] => Ok(None),
        [one] => Ok(Some(one)),
        many => Err(format!(
            "several files could be the called program: {}",
            many.join(", ")
        )),
    }
}

/// A file name's stem: the name without its folder and last extension.
fn stem_of(name: &str) -> String {
    Path::new(name)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// File names tried for a call, in order, without repeats.
fn candidates(r: ProgramRef<'_>, stem: &str) -> Vec<String> {
    let bases: Vec<String> = match r {
        ProgramRef::Number(n) => vec![
            format!("O{n:04}"),
            format!("O{n}"),
            format!("o{n:04}"),
            format!("o{n}"),
            format!("{n:04}"),
            format!("{n}"),
            format!("{stem}-{n}"),
        ],
        ProgramRef::Name(name) => vec![name.to_string()],
    };
    let exts: &[&str] = match r {
        ProgramRef::Number(_) => &["", ".nc", ".NC", ".ngc", ".NGC"],
        ProgramRef::Name(_) => &[".ngc", ".nc", ""],
    };
    let mut out: Vec<String> = Vec::new();
    for b in &bases {
        for e in exts {
            let n = format!("{b}{e}");
            if !out.contains(&n) {
                out.push(n);
            }
        }
    }
    out
}

impl<'a> Reader<'a> {
    /// `M98 P number L repeats` from the line just read.
    pub(super) fn call_number(&mut self, number: u64, repeats: u64) -> Result<(), Problem> {
        if repeats == 0 {
            return Ok(());
        }
        self.check_repeats(repeats)?;
        self.check_depth()?;
        let resolved = match self.resolver.as_mut() {
            Some(r) => r(ProgramRef::Number(number)).map_err(Problem::Subprogram)?,
            None => None,
        };
        if let Some(program) = resolved {
            let name = program.name.clone();
            let file = self.open(program)?;
            self.push_frame(
                file,
                FrameKind::Child {
                    number,
                    start: Mark::START,
                    left: repeats,
                },
                false,
            )?;
            self.emit(EventKind::Call {
                program: name,
                repeats,
            });
            return Ok(());
        }
        let body = self.find_program_number(number)?.ok_or_else(|| {
            Problem::Subprogram(format!(
                "M98 P{number}: no program {number} beside {} (the resolver found none) and no \
                 line O{number} in {}",
                self.files[0].name,
                self.file().name
            ))
        })?;
        let file = self.frame().file;
        let name = self.file().name.clone();
        self.push_frame(
            file,
            FrameKind::Child {
                number,
                start: body,
                left: repeats,
            },
            false,
        )?;
        self.seek(body)?;
        self.emit(EventKind::Call {
            program: format!("{name} O{number}").into(),
            repeats,
        });
        Ok(())
    }

    /// `o<label> call [args…]` from the line just read.
    pub(super) fn call_sub(&mut self, label: Label, args: &[f64]) -> Result<(), Problem> {
        self.check_depth()?;
        let file = self.frame().file;
        let (file, body) = match self.find_sub(&label)? {
            Some(b) => (file, b),
            None => {
                let name = match &label {
                    Label::Name(n) => n.to_string(),
                    Label::Number(n) => n.to_string(),
                };
                let resolved = match self.resolver.as_mut() {
                    Some(r) => r(ProgramRef::Name(&name)).map_err(Problem::Subprogram)?,
                    None => None,
                };
                let program = resolved.ok_or_else(|| {
                    Problem::Subprogram(format!(
                        "{label} call: no {label} sub in {} and no file for it (the resolver \
                         found none)",
                        self.file().name
                    ))
                })?;
                let child_name = program.name.clone();
                let child = self.open(program)?;
                // Look in the new file from its start, with it as the current file.
                self.push_frame(
                    child,
                    FrameKind::Sub {
                        label: label.clone(),
                    },
                    true,
                )?;
                let found = self.find_sub(&label)?;
                let body = found.ok_or_else(|| {
                    Problem::Subprogram(format!(
                        "{child_name} was found for {label} call but defines no {label} sub"
                    ))
                })?;
                self.vars.enter(args);
                self.seek(body)?;
                self.emit(EventKind::Call {
                    program: child_name,
                    repeats: 1,
                });
                return Ok(());
            }
        };
        let name = self.file().name.clone();
        self.push_frame(
            file,
            FrameKind::Sub {
                label: label.clone(),
            },
            true,
        )?;
        self.vars.enter(args);
        self.seek(body)?;
        self.emit(EventKind::Call {
            program: format!("{name} {label}").into(),
            repeats: 1,
        });
        Ok(())
    }

    /// `M99`, or `endsub`/`return` of `label`.
    pub(super) fn ret(&mut self, label: Option<&Label>) -> Result<(), Problem> {
        let frame = self.frames.last().ok_or(Problem::NoMotion)?;
        match (&frame.kind, label) {
            (FrameKind::Main, None) => {
                return Err(Problem::Unsupported(
                    "M99 in the main program: a Fanuc control would run the program again \
                     forever; end it with M2 or M30"
                        .into(),
                ));
            }
            (FrameKind::Main, Some(l)) => {
                return Err(Problem::Unbalanced(format!("{l} endsub outside a call")));
            }
            (FrameKind::Child { start, left, .. }, None) if *left > 1 => {
                let start = *start;
                self.frame_mut().kind.count_down();
                self.loops.truncate(self.frame().loops_base);
                self.seek(start)?;
                return Ok(());
            }
            (FrameKind::Child { .. }, None) => {}
            (FrameKind::Sub { label: l }, Some(given)) if l == given => {}
            (FrameKind::Sub { label: l }, _) => {
                let what = label.map_or("M99".to_string(), |g| format!("{g} endsub/return"));
                return Err(Problem::Unbalanced(format!("{what} inside {l} sub")));
            }
            (FrameKind::Child { number, .. }, Some(l)) => {
                return Err(Problem::Unbalanced(format!(
                    "{l} endsub/return inside program {number} (called by M98)"
                )));
            }
        }
        let frame = self.frames.pop().ok_or(Problem::NoMotion)?;
        self.loops.truncate(frame.loops_base);
        if frame.scoped {
            self.vars.leave();
        }
        if frame.file + 1 == self.files.len() && self.frame().file != frame.file {
            self.files.pop();
        }
        if let Some(back) = frame.return_to {
            self.seek(back)?;
        }
        self.emit(EventKind::Return);
        Ok(())
    }

    fn check_depth(&self) -> Result<(), Problem> {
        let depth = self.frames.len() - 1;
        if depth >= self.options.max_call_depth {
            return Err(Problem::Limit {
                what: "call nesting".into(),
                limit: self.options.max_call_depth as u64,
                hint: "calls nest deeper than this (a program calling itself?)".into(),
            });
        }
        Ok(())
    }

    fn open(&mut self, program: Program<'a>) -> Result<usize, Problem> {
        let id = self.intern(&program.name)?;
        self.files.push(OpenFile::new(program, id));
        Ok(self.files.len() - 1)
    }

    fn push_frame(&mut self, file: usize, kind: FrameKind, scoped: bool) -> Result<(), Problem> {
        let return_to = Some(self.next_mark());
        self.frames.push(Frame {
            file,
            kind,
            loops_base: self.loops.len(),
            return_to,
            scoped,
        });
        Ok(())
    }

    /// Looks through the current file for `label sub` (once per file: a look to the end notes
    /// every sub, and the file is not read again for another); leaves the file where it was.
    /// Returns the body's first line.
    fn find_sub(&mut self, label: &Label) -> Result<Option<Mark>, Problem> {
        let id = self.file().id;
        if let Some(body) = self.cache.sub(id, label) {
            return Ok(Some(body));
        }
        if self.cache.all_subs_known(id) {
            return Ok(None);
        }
        let back = self.next_mark();
        self.seek(Mark::START)?;
        let found = self.scan(|c, after, cache| {
            if let Head::OWord {
                label: l,
                keyword: OKeyword::Sub,
                ..
            } = &c.head
            {
                cache.set_sub(id, l.clone(), after);
                if l == label {
                    return Scan::Found;
                }
            }
            Scan::Continue
        })?;
        if found.is_none() {
            self.cache.set_all_subs_known(id);
        }
        self.seek(back)?;
        Ok(found.map(|(_, after)| after))
    }

    /// The line after `O number` in the current file (searched once per file and number).
    fn find_program_number(&mut self, number: u64) -> Result<Option<Mark>, Problem> {
        let id = self.file().id;
        if let Some(m) = self.cache.program(id, number) {
            return Ok(m);
        }
        let back = self.next_mark();
        self.seek(Mark::START)?;
        let found = self.scan(|c, _, _| match c.head {
            Head::ProgramNumber(n) if n == number => Scan::Found,
            _ => Scan::Continue,
        })?;
        self.seek(back)?;
        let body = found.map(|(_, after)| after);
        self.cache.set_program(id, number, body);
        Ok(body)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texts_are_resolved_by_the_same_names_and_ambiguity_is_an_error() {
        let files = vec![
            ("lens-2.nc".to_string(), "G1 X1\nM99\n".to_string()),
            (
                "pass.ngc".to_string(),
                "o<pass> sub\no<pass> endsub\n".to_string(),
            ),
            ("O0003.nc".to_string(), "M99\n".to_string()),
            ("3".to_string(), "M99\n".to_string()),
        ];
        let mut r = texts_beside("lens.nc", &files);
        let name = |p: Option<Program>| p.map(|p| p.name.to_string());
        assert_eq!(
            name(r(ProgramRef::Number(2)).unwrap()).as_deref(),
            Some("lens-2.nc")
        );
        assert_eq!(
            name(r(ProgramRef::Name("pass")).unwrap()).as_deref(),
            Some("pass.ngc")
        );
        assert_eq!(name(r(ProgramRef::Number(4)).unwrap()), None);
        let e = r(ProgramRef::Number(3)).unwrap_err();
        assert_eq!(e, "several files could be the called program: O0003.nc, 3");
    }

    #[test]
    fn candidate_names_for_numbers_and_names() {
        let c = candidates(ProgramRef::Number(12), "lens");
        assert_eq!(
            &c[..5],
            ["O0012", "O0012.nc", "O0012.NC", "O0012.ngc", "O0012.NGC"]
        );
        assert!(c.contains(&"lens-12.nc".to_string()));
        assert!(c.contains(&"12".to_string()));
        let c = candidates(ProgramRef::Number(1234), "x");
        assert_eq!(c.iter().filter(|n| *n == "O1234").count(), 1);
        assert_eq!(
            candidates(ProgramRef::Name("pass"), "x"),
            ["pass.ngc", "pass.nc", "pass"]
        );
    }
}

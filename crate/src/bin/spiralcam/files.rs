//! Files in and out, bounded and leaving nothing behind.
//!
//! **In**: a job, a data file or a points file is read only if it is a regular file (a device,
//! a FIFO or a directory is refused before anything is read from it: it is opened without
//! blocking and examined), no larger than its limit, and UTF-8.
//!
//! **Out**: every target is checked before planning: not a directory, not read-only, not one of
//! the inputs, no two the same. A regular file (or a new one) is written under a temporary name
//! beside it, created exclusively (`O_EXCL`: never through a link someone left there), and
//! renamed over the target only when the whole run has succeeded; on an error, a panic or a
//! signal the temporary is removed ([`crate::cancel`] removes it if the run does not stop in
//! time). A target that exists and is neither a regular file nor a directory (`/dev/null`, a
//! FIFO, a terminal) is written in place: it cannot be replaced atomically, and replacing it
//! would destroy the device.

use crate::{Failure, cancel};
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Read, Write};
use std::path::{Path, PathBuf};

/// Reads `path` as UTF-8 text: a regular file of at most `limit` bytes.
pub fn read_text(path: &Path, limit: u64) -> Result<String, String> {
    String::from_utf8(read_bytes(path, limit)?)
        .map_err(|e| format!("not UTF-8 text (at byte {})", e.utf8_error().valid_up_to()))
}

/// Reads `path`'s bytes: a regular file of at most `limit` bytes.
pub fn read_bytes(path: &Path, limit: u64) -> Result<Vec<u8>, String> {
    let file = open_regular(path)?;
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > limit {
        return Err(format!("larger than {limit} bytes, the most read"));
    }
    Ok(bytes)
}

/// Opens `path` for reading if it is a regular file.
fn open_regular(path: &Path) -> Result<File, String> {
    let mut options = OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        // A FIFO would block the open until a writer came; a device is refused below anyway.
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(|e| e.to_string())?;
    let meta = file.metadata().map_err(|e| e.to_string())?;
    if meta.is_dir() {
        return Err("is a directory, not a file".into());
    }
    if !meta.is_file() {
        return Err("is not a regular file (a device, a FIFO or a socket): not read".into());
    }
    Ok(file)
}

/// An output asked for on the command line.
#[derive(Clone)]
pub struct Target {
    /// The option that named it, for messages.
    pub flag: &'static str,
    /// The path.
    pub path: PathBuf,
}

/// The target's identity for comparison: its canonical path where it exists, else its
/// directory's canonical path and its name.
fn identity(path: &Path) -> PathBuf {
    if let Ok(p) = path.canonicalize() {
        return p;
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let dir = dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf());
    dir.join(path.file_name().unwrap_or_default())
}

/// Checks the targets before any work: none the same as another or as an input (the command
/// line is wrong: exit 2), each in an existing folder, not a directory and not read-only (a
/// file is wrong: exit 1).
pub fn check_targets(targets: &[Target], inputs: &[PathBuf]) -> Result<(), Failure> {
    let inputs: Vec<PathBuf> = inputs.iter().map(|p| identity(p)).collect();
    for (k, t) in targets.iter().enumerate() {
        let usage = |why: String| Failure::Usage(format!("{} {}: {why}", t.flag, t.path.display()));
        let bad = |why: String| Failure::Run(format!("{} {}: {why}", t.flag, t.path.display()));
        let id = identity(&t.path);
        if let Some(other) = targets[..k].iter().find(|o| identity(&o.path) == id) {
            return Err(usage(format!("the same file as {}", other.flag)));
        }
        if inputs.contains(&id) {
            return Err(usage(
                "is an input of the job: it would be overwritten".into(),
            ));
        }
        if t.path.as_os_str().is_empty() {
            return Err(usage("an empty file name".into()));
        }
        match std::fs::metadata(&t.path) {
            Ok(m) if m.is_dir() => return Err(bad("is a directory".into())),
            Ok(m) if m.is_file() && m.permissions().readonly() => {
                return Err(bad("is read-only: spiralcam does not replace it".into()));
            }
            Ok(_) => {}
            Err(_) => {
                let dir = t.path.parent().filter(|d| !d.as_os_str().is_empty());
                let dir = dir.unwrap_or(Path::new("."));
                if !dir.is_dir() {
                    return Err(bad(format!("the folder {} does not exist", dir.display())));
                }
            }
        }
    }
    Ok(())
}

/// Bytes an output file gathers before it writes them: a planned batch's text (about 800 KB)
/// is larger and goes to the file in one write without a copy through the buffer (a 1 MiB
/// buffer copied all 1.4 GB of a 28.4 M-point program once more: 0.1 s of its 2.9 s).
const WRITE_BUFFER: usize = 1 << 16;

/// A file being written: under a temporary name until [`OutputFile::commit`].
pub struct OutputFile {
    target: PathBuf,
    temp: Option<PathBuf>,
    /// The writer.
    pub writer: BufWriter<File>,
}

impl OutputFile {
    /// Starts writing `target` (checked by [`check_targets`]).
    pub fn create(target: &Path) -> Result<Self, Failure> {
        let fail = |e: std::io::Error| Failure::Run(format!("{}: {e}", target.display()));
        let special = std::fs::metadata(target).is_ok_and(|m| !m.is_file() && !m.is_dir());
        if special {
            let file = OpenOptions::new().write(true).open(target).map_err(fail)?;
            return Ok(Self {
                target: target.to_path_buf(),
                temp: None,
                writer: BufWriter::with_capacity(WRITE_BUFFER, file),
            });
        }
        let (file, temp) = create_temp(target).map_err(fail)?;
        Ok(Self {
            target: target.to_path_buf(),
            temp: Some(temp),
            writer: BufWriter::with_capacity(WRITE_BUFFER, file),
        })
    }

    /// Finishes the file: flushes it and renames it over the target.
    pub fn commit(mut self) -> Result<(), Failure> {
        let fail = |e: std::io::Error| Failure::Run(format!("{}: {e}", self.target.display()));
        self.writer.flush().map_err(fail)?;
        if let Some(temp) = self.temp.take() {
            let renamed = std::fs::rename(&temp, &self.target);
            cancel::forget(&temp);
            if let Err(e) = renamed {
                let _ = std::fs::remove_file(&temp);
                return Err(fail(e));
            }
        }
        Ok(())
    }
}

impl Drop for OutputFile {
    /// An output not committed is removed.
    fn drop(&mut self) {
        if let Some(temp) = self.temp.take() {
            let _ = std::fs::remove_file(&temp);
            cancel::forget(&temp);
        }
    }
}

/// The child programs of a program split past its size limit, written beside the main
/// program as `STEM-1.nc`, `STEM-2.nc`, … (each checked like every target, through its own
/// temporary), committed with the rest.
pub struct ChildOutputs {
    dir: PathBuf,
    /// The main program's file stem.
    pub stem: String,
    inputs: Vec<PathBuf>,
    files: Vec<OutputFile>,
}

impl ChildOutputs {
    /// Children beside `main`, none of which may be one of `inputs`.
    pub fn beside(main: &Path, inputs: Vec<PathBuf>) -> Self {
        let dir = main.parent().filter(|d| !d.as_os_str().is_empty());
        Self {
            dir: dir.unwrap_or(Path::new(".")).to_path_buf(),
            stem: main
                .file_stem()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned(),
            inputs,
            files: Vec::new(),
        }
    }

    /// Renames every child into place.
    pub fn commit(self) -> Result<(), Failure> {
        for f in self.files {
            f.commit()?;
        }
        Ok(())
    }
}

impl spiralcam::nc::program::ChildFiles for ChildOutputs {
    fn child(&mut self, number: usize, name: &str) -> std::io::Result<&mut dyn Write> {
        if number > self.files.len() {
            let path = self.dir.join(name);
            let target = Target {
                flag: "--nc (a child program)",
                path: path.clone(),
            };
            check_targets(&[target], &self.inputs)
                .map_err(|e| std::io::Error::other(e.to_string()))?;
            let file =
                OutputFile::create(&path).map_err(|e| std::io::Error::other(e.to_string()))?;
            self.files.push(file);
        }
        let file = self
            .files
            .get_mut(number - 1)
            .ok_or_else(|| std::io::Error::other(format!("child {number} out of order")))?;
        Ok(&mut file.writer)
    }
}

/// Creates a new file beside `target`, `.NAME.spiralcam-PID-K.partial`, exclusively.
fn create_temp(target: &Path) -> std::io::Result<(File, PathBuf)> {
    let dir = target.parent().filter(|d| !d.as_os_str().is_empty());
    let dir = dir.unwrap_or(Path::new("."));
    let name = target.file_name().unwrap_or_default().to_string_lossy();
    let mut last = None;
    for k in 0..100 {
        let temp = dir.join(format!(
            ".{name}.spiralcam-{}-{k}.partial",
            std::process::id()
        ));
        cancel::remember(&temp);
        match OpenOptions::new().write(true).create_new(true).open(&temp) {
            Ok(f) => return Ok((f, temp)),
            Err(e) => {
                cancel::forget(&temp);
                if e.kind() != std::io::ErrorKind::AlreadyExists {
                    return Err(e);
                }
                last = Some(e);
            }
        }
    }
    Err(last.unwrap_or_else(|| std::io::Error::other("no temporary name free")))
}

/// Writes `text` to `path` through a temporary (or in place for a special file).
pub fn write_file(path: &Path, text: &[u8]) -> Result<(), Failure> {
    let mut out = OutputFile::create(path)?;
    out.writer
        .write_all(text)
        .map_err(|e| Failure::Run(format!("{}: {e}", path.display())))?;
    out.commit()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("spiralcam-files-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_link_at_the_temporary_name_is_not_followed() {
        let dir = scratch("link");
        let victim = dir.join("victim");
        std::fs::write(&victim, "untouched").unwrap();
        let target = dir.join("out.nc");
        let first = dir.join(format!(
            ".out.nc.spiralcam-{}-0.partial",
            std::process::id()
        ));
        std::os::unix::fs::symlink(&victim, &first).unwrap();
        let mut out = OutputFile::create(&target).unwrap();
        out.writer.write_all(b"program").unwrap();
        out.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "untouched");
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "program");
        assert!(
            std::fs::symlink_metadata(&first)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_output_dropped_unfinished_leaves_nothing() {
        let dir = scratch("drop");
        let target = dir.join("out.nc");
        {
            let mut out = OutputFile::create(&target).unwrap();
            out.writer.write_all(b"half a program").unwrap();
        }
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn only_regular_files_are_read_and_only_up_to_the_limit() {
        let dir = scratch("read");
        let file = dir.join("a.txt");
        std::fs::write(&file, "12345").unwrap();
        assert_eq!(read_text(&file, 5).unwrap(), "12345");
        assert!(
            read_text(&file, 4)
                .unwrap_err()
                .contains("larger than 4 bytes")
        );
        assert!(
            read_text(Path::new("/dev/zero"), 5)
                .unwrap_err()
                .contains("not a regular file")
        );
        assert!(read_text(&dir, 5).unwrap_err().contains("is a directory"));
        std::fs::write(&file, [0x66, 0xff, 0x66]).unwrap();
        assert!(
            read_text(&file, 5)
                .unwrap_err()
                .contains("not UTF-8 text (at byte 1)")
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

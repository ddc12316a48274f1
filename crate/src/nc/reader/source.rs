//! Where a program's text comes from: a [`Source`] hands out one line at a time and can go back
//! to a line it handed out before (loops, `GOTO`, subprograms), so the reader holds one line,
//! never the program. [`TextSource`] reads text already in memory (what the page has);
//! [`StreamSource`] streams any `Read + Seek` (a file on disk) through an 8 KiB buffer, so a
//! 30 M-block program costs its buffer, not its size.
//!
//! Lines end at `\n`; a `\r` before it is dropped. A line longer than the reader's limit
//! ([`super::MAX_LINE_BYTES`]) is reported as such, never read whole into memory.

use std::io::{self, BufRead, BufReader, Read, Seek, SeekFrom};

/// What [`Source::read_line`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineRead {
    /// A line is in the buffer.
    Line,
    /// The line is longer than the limit (the buffer holds its start).
    TooLong,
    /// The text has ended.
    End,
}

/// A program's text, read line by line, able to return to the start of an earlier line.
pub trait Source {
    /// Reads the next line, without its end, into `line` (cleared first); at most `max` bytes.
    fn read_line(&mut self, line: &mut Vec<u8>, max: usize) -> io::Result<LineRead>;
    /// The byte offset of the next line.
    fn offset(&self) -> u64;
    /// Makes the line starting at byte `offset` the next one.
    fn seek(&mut self, offset: u64) -> io::Result<()>;
}

/// Text in memory: a `String`, `&str`, `Vec<u8>`, `Arc<[u8]>`, anything that is bytes.
#[derive(Debug, Clone)]
pub struct TextSource<T> {
    text: T,
    pos: usize,
}

impl<T: AsRef<[u8]>> TextSource<T> {
    /// A source reading `text` from its start.
    pub fn new(text: T) -> Self {
        Self { text, pos: 0 }
    }
}

impl<T: AsRef<[u8]>> Source for TextSource<T> {
    fn read_line(&mut self, line: &mut Vec<u8>, max: usize) -> io::Result<LineRead> {
        line.clear();
        let rest = &self.text.as_ref()[self.pos..];
        if rest.is_empty() {
            return Ok(LineRead::End);
        }
        let (len, next) = match rest.iter().position(|&b| b == b'\n') {
            Some(i) => (i, i + 1),
            None => (rest.len(), rest.len()),
        };
        self.pos += next;
        let body = strip_cr(&rest[..len]);
        if body.len() > max {
            line.extend_from_slice(&body[..max]);
            return Ok(LineRead::TooLong);
        }
        line.extend_from_slice(body);
        Ok(LineRead::Line)
    }

    fn offset(&self) -> u64 {
        self.pos as u64
    }

    fn seek(&mut self, offset: u64) -> io::Result<()> {
        let len = self.text.as_ref().len();
        match usize::try_from(offset) {
            Ok(o) if o <= len => {
                self.pos = o;
                Ok(())
            }
            _ => Err(io::Error::other(format!(
                "offset {offset} is past the end of the text ({len} bytes)"
            ))),
        }
    }
}

/// Text streamed from a reader that can seek, such as a [`std::fs::File`].
#[derive(Debug)]
pub struct StreamSource<R> {
    inner: BufReader<R>,
    pos: u64,
}

impl<R: Read + Seek> StreamSource<R> {
    /// A source reading `inner` from its current position, which counts as offset 0 only if
    /// it is the start: give a freshly opened file.
    pub fn new(inner: R) -> Self {
        Self {
            inner: BufReader::with_capacity(8192, inner),
            pos: 0,
        }
    }
}

impl<R: Read + Seek> Source for StreamSource<R> {
    fn read_line(&mut self, line: &mut Vec<u8>, max: usize) -> io::Result<LineRead> {
        line.clear();
        let mut any = false;
        let mut too_long = false;
        loop {
            let buf = self.inner.fill_buf()?;
            if buf.is_empty() {
                break;
            }
            any = true;
            let (take, done) = match buf.iter().position(|&b| b == b'\n') {
                Some(i) => (i, true),
                None => (buf.len(), false),
            };
            let room = (max + 1).saturating_sub(line.len());
            if take > room {
                too_long = true;
            }
            line.extend_from_slice(&buf[..take.min(room)]);
            let used = take + usize::from(done);
            self.inner.consume(used);
            self.pos += used as u64;
            if done {
                break;
            }
        }
        if !any {
            return Ok(LineRead::End);
        }
        if line.last() == Some(&b'\r') && !too_long {
            line.pop();
        }
        if too_long || line.len() > max {
            line.truncate(max);
            return Ok(LineRead::TooLong);
        }
        Ok(LineRead::Line)
    }

    fn offset(&self) -> u64 {
        self.pos
    }

    fn seek(&mut self, offset: u64) -> io::Result<()> {
        let delta = i64::try_from(offset).ok().zip(i64::try_from(self.pos).ok());
        match delta {
            // Within or near the buffer: seek_relative keeps what is buffered.
            Some((to, from)) => self.inner.seek_relative(to - from)?,
            None => {
                self.inner.seek(SeekFrom::Start(offset))?;
            }
        }
        self.pos = offset;
        Ok(())
    }
}

fn strip_cr(line: &[u8]) -> &[u8] {
    line.strip_suffix(b"\r").unwrap_or(line)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Cursor;

    fn lines(s: &mut dyn Source, max: usize) -> Vec<(String, LineRead, u64)> {
        let mut out = Vec::new();
        let mut buf = Vec::new();
        loop {
            let at = s.offset();
            let r = s.read_line(&mut buf, max).unwrap();
            if r == LineRead::End {
                return out;
            }
            out.push((String::from_utf8(buf.clone()).unwrap(), r, at));
        }
    }

    #[test]
    fn text_and_stream_sources_agree_on_lines_offsets_and_long_lines() {
        let text = "G1 X1\r\nC2 X3\n\nabcdefghij\nlast";
        for max in [4, 5, 10, 100] {
            let a = lines(&mut TextSource::new(text), max);
            let mut stream = StreamSource::new(Cursor::new(text.as_bytes().to_vec()));
            let b = lines(&mut stream, max);
            assert_eq!(a, b, "max {max}");
        }
        let a = lines(&mut TextSource::new(text), 5);
        assert_eq!(a[0], ("G1 X1".into(), LineRead::Line, 0));
        assert_eq!(a[1], ("C2 X3".into(), LineRead::Line, 7));
        assert_eq!(a[2], ("".into(), LineRead::Line, 13));
        assert_eq!(a[3], ("abcde".into(), LineRead::TooLong, 14));
        assert_eq!(a[4], ("last".into(), LineRead::Line, 25));
    }

    #[test]
    fn seeking_back_rereads_the_same_lines() {
        let text: String = (0..5000).map(|i| format!("N{i} X{i}\n")).collect();
        let mut stream = StreamSource::new(Cursor::new(text.clone().into_bytes()));
        let mut mem = TextSource::new(text);
        let mut buf = Vec::new();
        let mut marks = Vec::new();
        for _ in 0..3000 {
            marks.push(stream.offset());
            stream.read_line(&mut buf, 100).unwrap();
        }
        for &m in marks.iter().rev().step_by(97) {
            stream.seek(m).unwrap();
            mem.seek(m).unwrap();
            let mut other = Vec::new();
            stream.read_line(&mut buf, 100).unwrap();
            mem.read_line(&mut other, 100).unwrap();
            assert_eq!(buf, other);
            assert_eq!(stream.offset(), mem.offset());
        }
        assert!(mem.seek(1 << 40).is_err());
    }
}

//! The text of a designer's file from its bytes. OpticStudio writes `.zmx` files in UTF-16
//! little-endian with a byte-order mark (the public readers try UTF-16 first: ray-optics
//! `zmxread.py` `read_lens_file`, optiland's Zemax parser; the vendors' example files in
//! ray-optics' tests are UTF-16LE with `FF FE`), older versions in ASCII or a Windows code page,
//! and CODE V writes plain text.
//!
//! A byte-order mark decides: `FF FE` UTF-16LE, `FE FF` UTF-16BE, `EF BB BF` UTF-8. Without one,
//! bytes that are valid UTF-8 (ASCII included) are read as UTF-8 and anything else as
//! ISO-8859-1 (every byte one character, as Python's `iso-8859-1` codec, the readers' last
//! resort). A NUL byte without a UTF-16 mark is refused: it is UTF-16 without its byte-order
//! mark, which cannot be told from binary data. An odd number of UTF-16 bytes or an unpaired
//! surrogate is an error naming the byte.

/// How the text was stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    /// UTF-8 or ASCII (with or without a byte-order mark).
    Utf8,
    /// UTF-16 little-endian, with its byte-order mark.
    Utf16Le,
    /// UTF-16 big-endian, with its byte-order mark.
    Utf16Be,
    /// ISO-8859-1 (Latin-1): bytes that are not UTF-8.
    Latin1,
}

impl Encoding {
    /// The encoding's name.
    pub fn name(self) -> &'static str {
        match self {
            Encoding::Utf8 => "UTF-8",
            Encoding::Utf16Le => "UTF-16LE",
            Encoding::Utf16Be => "UTF-16BE",
            Encoding::Latin1 => "ISO-8859-1",
        }
    }
}

/// Decodes `bytes`; the error says what is wrong and at which byte.
pub fn decode(bytes: &[u8]) -> Result<(String, Encoding), String> {
    if let Some(rest) = bytes.strip_prefix(&[0xFF, 0xFE]) {
        return utf16(rest, u16::from_le_bytes).map(|t| (t, Encoding::Utf16Le));
    }
    if let Some(rest) = bytes.strip_prefix(&[0xFE, 0xFF]) {
        return utf16(rest, u16::from_be_bytes).map(|t| (t, Encoding::Utf16Be));
    }
    let body = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]).unwrap_or(bytes);
    if let Some(k) = body.iter().position(|&b| b == 0) {
        let k = k + bytes.len() - body.len();
        return Err(format!(
            "byte {k} is NUL: UTF-16 text needs its byte-order mark (FF FE or FE FF), and other \
             binary data is not a designer's text file"
        ));
    }
    match std::str::from_utf8(body) {
        Ok(t) => Ok((t.to_string(), Encoding::Utf8)),
        Err(_) => Ok((body.iter().map(|&b| b as char).collect(), Encoding::Latin1)),
    }
}

/// UTF-16 units from byte pairs (after the 2-byte mark), then the text.
fn utf16(rest: &[u8], unit: fn([u8; 2]) -> u16) -> Result<String, String> {
    if !rest.len().is_multiple_of(2) {
        return Err(format!(
            "UTF-16 text of an odd number of bytes ({}): the last byte is cut off",
            rest.len() + 2
        ));
    }
    let units = rest.chunks_exact(2).map(|p| unit([p[0], p[1]]));
    let mut text = String::with_capacity(rest.len() / 2);
    for (k, c) in char::decode_utf16(units).enumerate() {
        match c {
            Ok(c) => text.push(c),
            Err(e) => {
                return Err(format!(
                    "byte {}: unpaired UTF-16 surrogate {:04X}",
                    2 + 2 * k,
                    e.unpaired_surrogate()
                ));
            }
        }
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn utf16le(text: &str) -> Vec<u8> {
        let mut b = vec![0xFF, 0xFE];
        b.extend(text.encode_utf16().flat_map(u16::to_le_bytes));
        b
    }

    #[test]
    fn every_encoding_the_design_tools_write_reads_the_same_text() {
        let text = "UNIT MM X W X CM MR CPMM\r\nSURF 1\r\n  COMM Linse Ø25 µm\r\n";
        assert_eq!(
            decode(&utf16le(text)).unwrap(),
            (text.into(), Encoding::Utf16Le)
        );
        let mut be = vec![0xFE, 0xFF];
        be.extend(text.encode_utf16().flat_map(u16::to_be_bytes));
        assert_eq!(decode(&be).unwrap(), (text.into(), Encoding::Utf16Be));
        let mut bom = vec![0xEF, 0xBB, 0xBF];
        bom.extend(text.as_bytes());
        assert_eq!(decode(&bom).unwrap(), (text.into(), Encoding::Utf8));
        assert_eq!(
            decode(text.as_bytes()).unwrap(),
            (text.into(), Encoding::Utf8)
        );
        let latin1: Vec<u8> = text.chars().map(|c| c as u32 as u8).collect();
        assert_eq!(decode(&latin1).unwrap(), (text.into(), Encoding::Latin1));
    }

    #[test]
    fn broken_utf16_and_nul_bytes_are_refused_with_the_byte() {
        let mut odd = utf16le("SURF 1");
        odd.push(b'x');
        assert!(
            decode(&odd)
                .unwrap_err()
                .contains("odd number of bytes (15)")
        );
        let mut lone = vec![0xFF, 0xFE, b'A', 0];
        lone.extend([0x00, 0xD8, b'B', 0]);
        assert_eq!(
            decode(&lone).unwrap_err(),
            "byte 4: unpaired UTF-16 surrogate D800"
        );
        let no_mark: Vec<u8> = "SURF".encode_utf16().flat_map(u16::to_le_bytes).collect();
        assert!(decode(&no_mark).unwrap_err().starts_with("byte 1 is NUL"));
    }
}

//! Several files in one download: a program split into a main program and child programs
//! (`program.max_program_bytes`) reaches the user as one zip archive (PKWARE APPNOTE, deflate),
//! written by the `zip` crate, with the files in the order given (the main program first, then
//! the children in the order it calls them) and no directories.

use std::io::Write;

/// A file of a bundle: its name and contents.
pub type NamedFile = (String, Vec<u8>);

/// The zip archive of `files`.
pub fn zip_files(files: &[NamedFile]) -> Result<Vec<u8>, String> {
    let capacity = files.iter().map(|(_, b)| b.len() / 3).sum::<usize>() + 4096;
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::with_capacity(capacity)));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        .large_file(files.iter().any(|(_, b)| b.len() as u64 >= u32::MAX as u64));
    for (name, bytes) in files {
        zip.start_file(name.as_str(), options)
            .map_err(|e| format!("zip: {name}: {e}"))?;
        zip.write_all(bytes)
            .map_err(|e| format!("zip: {name}: {e}"))?;
    }
    let out = zip.finish().map_err(|e| format!("zip: {e}"))?;
    Ok(out.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Read;

    #[test]
    fn a_zip_gives_back_its_files_in_order() {
        let files: Vec<NamedFile> = vec![
            ("part.nc".into(), b"%\nM98 P1\nM30\n".repeat(100)),
            (
                "part-1.nc".into(),
                b"O1\nC0.5 X1.0 Z0.0\nM99\n".repeat(1000),
            ),
            ("empty.nc".into(), Vec::new()),
        ];
        let bytes = zip_files(&files).expect("zip");
        let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes)).expect("archive");
        assert_eq!(archive.len(), files.len());
        for (i, (name, contents)) in files.iter().enumerate() {
            let mut f = archive.by_index(i).expect("entry");
            assert_eq!(f.name().expect("name"), name.as_str());
            let mut back = Vec::new();
            f.read_to_end(&mut back).expect("read");
            assert_eq!(&back, contents, "{name}");
        }
    }
}

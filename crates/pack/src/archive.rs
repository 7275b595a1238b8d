//! The pack zip: deterministic and written atomically.
//!
//! Entries are sorted and carry a fixed timestamp and permissions, so identical inputs give
//! byte-identical zips. The zip is written to a temporary file beside the target and renamed
//! into place, so a failed or interrupted build never leaves a partial zip behind.

use std::io::Write;
use std::path::Path;

use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

/// Writes `entries` (path inside the zip, contents) to `target`.
pub fn write_zip(target: &Path, entries: &[(String, &[u8])]) -> std::io::Result<u64> {
    let dir = target.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)?;
    let file_name = target.file_name().ok_or_else(|| std::io::Error::other("the zip path names no file"))?;
    let temp = dir.join(format!(".{}.{}.tmp", file_name.to_string_lossy(), std::process::id()));
    let result = write_to(&temp, entries).and_then(|()| std::fs::rename(&temp, target));
    if result.is_err() {
        let _ = std::fs::remove_file(&temp);
    }
    result?;
    Ok(std::fs::metadata(target)?.len())
}

fn write_to(path: &Path, entries: &[(String, &[u8])]) -> std::io::Result<()> {
    let mut sorted: Vec<&(String, &[u8])> = entries.iter().collect();
    sorted.sort_by(|a, b| a.0.cmp(&b.0));
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Deflated)
        .compression_level(Some(9))
        .last_modified_time(DateTime::default())
        .unix_permissions(0o644);
    let mut zip = ZipWriter::new(std::fs::File::create(path)?);
    for (name, data) in sorted {
        zip.start_file(name.as_str(), options).map_err(std::io::Error::other)?;
        zip.write_all(data)?;
    }
    let file = zip.finish().map_err(std::io::Error::other)?;
    file.sync_all()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_inputs_give_identical_bytes() {
        let dir = std::env::temp_dir().join(format!("tidepack-archive-{}", std::process::id()));
        let a = dir.join("a.zip");
        let b = dir.join("b.zip");
        let entries = vec![("shaders/b.txt".to_string(), &b"two"[..]), ("shaders/a.txt".to_string(), &b"one"[..])];
        write_zip(&a, &entries).unwrap();
        std::thread::sleep(std::time::Duration::from_millis(1100));
        let mut reversed = entries.clone();
        reversed.reverse();
        write_zip(&b, &reversed).unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
        let leftovers: Vec<_> = std::fs::read_dir(&dir).unwrap().filter_map(|e| e.ok()).filter(|e| e.file_name().to_string_lossy().ends_with(".tmp")).collect();
        assert!(leftovers.is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

//! The rules every input file is read by, whoever reads it (the commands
//! through the driver's `files`, the language server directly): a regular
//! file (a symbolic link to one is followed), of bounded size, read with a
//! bound. A device or a FIFO named by mistake, or planted by a symbolic
//! link (`plant.json -> /dev/zero`), must not hang the reader or exhaust
//! its memory, and a file that grows while it is read is cut at the limit.
//! They live here, below the compiler, so that the language server (which
//! links only the compiler and this crate) and the commands share one
//! implementation.

use std::fs::{self, Metadata};
use std::io::{self, Read};
use std::path::Path;

/// The largest input file `linc` reads: far above any real action file or
/// database (the guide's largest are kilobytes; 50 MB of generated source
/// is accepted), far below what would exhaust a build machine's memory.
pub const MAX_INPUT_BYTES: u64 = 256 << 20;

/// What a file is, in words, when it is not a regular file.
pub fn kind(meta: &Metadata) -> Option<&'static str> {
    let t = meta.file_type();
    if t.is_file() {
        return None;
    }
    if t.is_symlink() {
        return Some("a symbolic link");
    }
    if t.is_dir() {
        return Some("a directory");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_char_device() {
            return Some("a character device");
        }
        if t.is_block_device() {
            return Some("a block device");
        }
        if t.is_fifo() {
            return Some("a FIFO (named pipe)");
        }
        if t.is_socket() {
            return Some("a socket");
        }
    }
    Some("not a regular file")
}

fn not_regular(what: &str) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, format!("it is {what}, not a regular file"))
}

/// The error of a file over `limit` bytes.
pub fn too_large(limit: u64) -> io::Error {
    let size = if limit >= 1 << 20 { format!("{} MiB", limit >> 20) } else { format!("{limit} byte") };
    io::Error::new(io::ErrorKind::InvalidInput, format!("the file is larger than the {size} input limit"))
}

/// Opens `path` for reading without waiting: with `O_NONBLOCK`, opening a
/// FIFO that no one writes returns at once (instead of blocking until a
/// writer comes), so a name swapped for a FIFO after the check by name is
/// still refused by the check on the open file.
fn open(path: &Path) -> io::Result<fs::File> {
    let mut options = fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    options.open(path)
}

/// Reads an input file: a regular file (symlinks to one are followed) of
/// at most `limit` bytes, with the metadata of the file actually read (the
/// driver remembers inputs by it). Anything else is an error the commands
/// print as E0900 (file cannot be read) and the language server treats as
/// no file.
pub fn read_file(path: &Path, limit: u64) -> io::Result<(Vec<u8>, Metadata)> {
    // Checked before opening: some devices act when opened.
    if let Some(what) = kind(&fs::metadata(path)?) {
        return Err(not_regular(what));
    }
    let file = open(path)?;
    // Checked again on the open file, in case the name changed in between.
    let meta = file.metadata()?;
    if let Some(what) = kind(&meta) {
        return Err(not_regular(what));
    }
    if meta.len() > limit {
        return Err(too_large(limit));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // The length can grow while reading (or lie, as in /proc): read one
    // byte more than the limit to notice.
    file.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(limit));
    }
    Ok((bytes, meta))
}

/// [`read_file`] for text: the bytes must be UTF-8.
pub fn read_text(path: &Path, limit: u64) -> io::Result<String> {
    utf8(read_file(path, limit)?.0)
}

/// The text of an input's bytes, or the error of one that is not UTF-8.
pub fn utf8(bytes: Vec<u8>) -> io::Result<String> {
    String::from_utf8(bytes)
        .map_err(|_| io::Error::new(io::ErrorKind::InvalidData, "stream did not contain valid UTF-8"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("linc-format-input-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).expect("dir");
        dir
    }

    #[test]
    fn inputs_up_to_the_limit_are_read_and_larger_ones_refused() {
        let dir = scratch("limit");
        let p = dir.join("f");
        fs::write(&p, [7u8; 100]).expect("write");
        assert_eq!(read_file(&p, 100).expect("at the limit").0.len(), 100);
        let e = read_file(&p, 99).expect_err("over the limit");
        assert_eq!(e.kind(), io::ErrorKind::InvalidInput);
        assert_eq!(e.to_string(), "the file is larger than the 99 byte input limit");
        assert_eq!(MAX_INPUT_BYTES, 256 * 1024 * 1024);
        assert_eq!(too_large(MAX_INPUT_BYTES).to_string(), "the file is larger than the 256 MiB input limit");
    }

    #[test]
    fn text_inputs_must_be_utf8() {
        let dir = scratch("utf8");
        let p = dir.join("f");
        fs::write(&p, b"ok \xff").expect("write");
        assert_eq!(read_text(&p, 100).expect_err("not UTF-8").kind(), io::ErrorKind::InvalidData);
        fs::write(&p, "ok é").expect("write");
        assert_eq!(read_text(&p, 100).expect("text"), "ok é");
    }

    #[test]
    fn directories_are_refused() {
        let dir = scratch("dirs");
        assert_eq!(read_file(&dir, 100).expect_err("a directory").to_string(), "it is a directory, not a regular file");
    }

    /// A link to `/dev/zero` would read forever; a FIFO no one writes would
    /// block forever. Both are refused at once.
    #[cfg(target_os = "linux")]
    #[test]
    fn devices_and_fifos_are_refused_even_behind_a_link() {
        let dir = scratch("devices");
        let link = dir.join("plant.json");
        std::os::unix::fs::symlink("/dev/zero", &link).expect("link");
        let e = read_file(&link, MAX_INPUT_BYTES).expect_err("/dev/zero");
        assert_eq!(e.to_string(), "it is a character device, not a regular file");
        let fifo = dir.join("fifo.json");
        let c = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).expect("path");
        // SAFETY: `c` is a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0, "mkfifo");
        let e = read_file(&fifo, MAX_INPUT_BYTES).expect_err("a FIFO");
        assert_eq!(e.to_string(), "it is a FIFO (named pipe), not a regular file");
        // Opened without the check by name (as after a swap), the open
        // returns at once and the check on the handle refuses it.
        let file = open(&fifo).expect("opens without a writer");
        assert_eq!(kind(&file.metadata().expect("meta")), Some("a FIFO (named pipe)"));
    }

    /// A file longer than its size said (it grew, or it is one of /proc's,
    /// which say 0) is read up to the limit and no further.
    #[cfg(target_os = "linux")]
    #[test]
    fn the_read_stops_at_the_limit_whatever_the_size_said() {
        let status = Path::new("/proc/self/status");
        assert_eq!(fs::metadata(status).expect("meta").len(), 0, "/proc says 0 bytes");
        assert!(read_file(status, 1 << 20).expect("read").0.len() > 100);
        assert_eq!(
            read_file(status, 10).expect_err("cut").to_string(),
            "the file is larger than the 10 byte input limit"
        );
    }
}

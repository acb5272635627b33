//! Every file `linc` reads or writes goes through here, so that one set of
//! rules protects them all: inputs are regular files of bounded size (a
//! device or a FIFO given by mistake must not hang the command or exhaust
//! memory), and outputs are written so that an interrupted run never
//! leaves a torn one.

use std::fs::{self, Metadata};
use std::io::{self, Read, Write};
use std::path::Path;

/// The largest input file `linc` reads: far above any real action file or
/// database (the guide's largest are kilobytes; 50 MB of generated source
/// is accepted), far below what would exhaust a build machine's memory.
pub const MAX_INPUT_BYTES: u64 = 256 << 20;

/// What a file is, in words, when it is not a regular file.
fn kind(meta: &Metadata) -> Option<&'static str> {
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

fn too_large(limit: u64) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, format!("the file is larger than the {} MiB input limit", limit >> 20))
}

/// Reads an input file: a regular file (symlinks to one are followed) of at
/// most [`MAX_INPUT_BYTES`]. Anything else is an error the callers print as
/// E0900 (file cannot be read), so `linc check /dev/zero` fails at once.
pub fn read_input(path: &Path) -> io::Result<Vec<u8>> {
    read_limited(path, MAX_INPUT_BYTES)
}

/// [`read_input`] for text: the bytes must be UTF-8.
pub fn read_input_text(path: &Path) -> io::Result<String> {
    String::from_utf8(read_input(path)?)
        .map_err(|_| io::Error::new(io::ErrorKind::InvalidData, "stream did not contain valid UTF-8"))
}

fn read_limited(path: &Path, limit: u64) -> io::Result<Vec<u8>> {
    // Checked before opening: opening a FIFO would block until a writer came.
    if let Some(what) = kind(&fs::metadata(path)?) {
        return Err(not_regular(what));
    }
    let file = fs::File::open(path)?;
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
    Ok(bytes)
}

/// Writes `bytes` to a temporary file beside `path`, then renames it over
/// `path` (atomic on one file system).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("out");
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("linc-files-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).expect("scratch");
        dir
    }

    #[test]
    fn inputs_up_to_the_limit_are_read_and_larger_ones_refused() {
        let dir = scratch("limit");
        let p = dir.join("f");
        fs::write(&p, [7u8; 100]).expect("write");
        assert_eq!(read_limited(&p, 100).expect("at the limit").len(), 100);
        let e = read_limited(&p, 99).expect_err("over the limit");
        assert_eq!(e.kind(), io::ErrorKind::InvalidInput);
        assert_eq!(MAX_INPUT_BYTES, 256 * 1024 * 1024);
        assert!(too_large(MAX_INPUT_BYTES).to_string().contains("256 MiB"));
    }

    #[test]
    fn text_inputs_must_be_utf8() {
        let dir = scratch("utf8");
        let p = dir.join("f");
        fs::write(&p, b"ok \xff").expect("write");
        assert_eq!(read_input_text(&p).expect_err("not UTF-8").kind(), io::ErrorKind::InvalidData);
        assert_eq!(read_input(&p).expect("bytes"), b"ok \xff");
    }

    #[test]
    fn directories_are_not_inputs() {
        let dir = scratch("dirs");
        let e = read_input(&dir).expect_err("a directory");
        assert_eq!(e.to_string(), "it is a directory, not a regular file");
    }
}

//! Every file `linc` reads or writes goes through here, so that one set of
//! rules protects them all: inputs are regular files of bounded size (a
//! device or a FIFO given by mistake must not hang the command or exhaust
//! memory), and outputs replace a regular file atomically or not at all
//! (never a link, a device, a FIFO or one of the inputs).

use linc_compiler::diag::Problems;
use linc_format::Code;
use std::fmt;
use std::fs::{self, Metadata};
use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The largest input file `linc` reads (the rules are `linc_format::input`'s,
/// which the language server shares).
pub use linc_format::input::MAX_INPUT_BYTES;
use linc_format::input::{kind, read_file};

/// Every file this process has read as an input, by identity, with the
/// name it was read by. No output may replace one of them, whichever
/// command, option or spelling names it: an output is checked against this
/// list when it is created ([`AtomicFile::create`]), besides the checks a
/// command makes before it starts ([`check_output`]).
static READ: Mutex<Vec<(Identity, PathBuf)>> = Mutex::new(Vec::new());

/// What makes two names one file: device and inode (hard links and
/// symlinks included); elsewhere the canonical path.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Identity {
    #[cfg(unix)]
    Inode(u64, u64),
    #[cfg(not(unix))]
    Path(PathBuf),
}

fn identity(path: &Path, meta: &Metadata) -> Identity {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let _ = path;
        Identity::Inode(meta.dev(), meta.ino())
    }
    #[cfg(not(unix))]
    {
        let _ = meta;
        Identity::Path(fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()))
    }
}

fn remember_input(path: &Path, meta: &Metadata) {
    if let Ok(mut read) = READ.lock() {
        let id = identity(path, meta);
        if !read.iter().any(|(i, _)| *i == id) {
            read.push((id, path.to_path_buf()));
        }
    }
}

/// The input (as it was named when read) that `meta` is, if any.
fn read_as_input(path: &Path, meta: &Metadata) -> Option<PathBuf> {
    let id = identity(path, meta);
    READ.lock().ok()?.iter().find(|(i, _)| *i == id).map(|(_, p)| p.clone())
}

/// Reads an input file: a regular file (symlinks to one are followed) of at
/// most [`MAX_INPUT_BYTES`]. Anything else is an error the callers print as
/// E0900 (file cannot be read), so `linc check /dev/zero` fails at once.
/// The file is remembered as an input, which no output may replace.
pub fn read_input(path: &Path) -> io::Result<Vec<u8>> {
    read_limited(path, MAX_INPUT_BYTES, true)
}

/// Reads a file that the same command writes again by design (the
/// retentive state of `--state`): like [`read_input`], but not remembered
/// as an input, so it may be saved over.
pub fn read_in_out(path: &Path) -> io::Result<Vec<u8>> {
    read_limited(path, MAX_INPUT_BYTES, false)
}

/// [`read_input`] for text: the bytes must be UTF-8.
pub fn read_input_text(path: &Path) -> io::Result<String> {
    linc_format::input::utf8(read_input(path)?)
}

fn read_limited(path: &Path, limit: u64, remember: bool) -> io::Result<Vec<u8>> {
    let (bytes, meta) = read_file(path, limit)?;
    if remember {
        remember_input(path, &meta);
    }
    Ok(bytes)
}

/// An output file `linc` will not write, or could not write: a refused
/// request, as [`Problems`] like any other.
#[derive(Debug)]
pub struct Refused {
    pub code: Code,
    pub message: String,
}

impl Refused {
    pub fn diagnostic(&self) -> linc_compiler::Diagnostic {
        linc_compiler::Diagnostic::command(self.code, self.message.clone())
    }
}

impl From<Refused> for Problems {
    fn from(r: Refused) -> Problems {
        Problems::refusal(r.diagnostic())
    }
}

impl fmt::Display for Refused {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

fn cant_write(path: &Path, e: impl fmt::Display) -> Refused {
    Refused { code: Code::E0900, message: format!("can't write `{}`: {e}", path.display()) }
}

/// The existing file at `path` (not following a symlink), if any; E0901 if
/// it is not a regular file. Replacing a symlink, device or FIFO would
/// destroy something that is not ours.
fn existing_output(path: &Path) -> Result<Option<Metadata>, Refused> {
    match fs::symlink_metadata(path) {
        Ok(meta) => match kind(&meta) {
            None => Ok(Some(meta)),
            Some(what) => Err(Refused {
                code: Code::E0901,
                message: format!("won't write `{}`: it is {what}, not a regular file", path.display()),
            }),
        },
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(cant_write(path, e)),
    }
}

/// Whether two metadata describe the same file (hard links included).
fn same_file(a: &Metadata, b: &Metadata) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        a.dev() == b.dev() && a.ino() == b.ino()
    }
    #[cfg(not(unix))]
    {
        let _ = (a, b);
        false
    }
}

fn is_input(out: &Path, input: &Path) -> Refused {
    Refused {
        code: Code::E0902,
        message: format!("won't write `{}`: it is the input `{}`", out.display(), input.display()),
    }
}

/// Checks, before any work is done, that `out` may be written: E0901 if it
/// exists and is not a regular file, E0902 if it is one of `inputs`, or a
/// file already read, under any spelling, hard link or symlink (writing it
/// would destroy the input).
pub fn check_output(out: &Path, inputs: &[&Path]) -> Result<(), Refused> {
    let Ok(target) = fs::metadata(out) else {
        // Nothing there (or a dangling link): no input can be overwritten.
        return existing_output(out).map(|_| ());
    };
    let canonical = fs::canonicalize(out).ok();
    for input in inputs {
        let same = fs::metadata(input).is_ok_and(|m| same_file(&m, &target))
            || (canonical.is_some() && fs::canonicalize(input).ok() == canonical);
        if same {
            return Err(is_input(out, input));
        }
    }
    if let Some(input) = read_as_input(out, &target) {
        return Err(is_input(out, &input));
    }
    existing_output(out).map(|_| ())
}

/// Where a name would be written: its directory resolved (links, `..`,
/// `.`) and its file name, so `out.json`, `./out.json` and
/// `dir/../out.json` are one place even before the file exists.
fn destination(path: &Path) -> PathBuf {
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    match (fs::canonicalize(dir), path.file_name()) {
        (Ok(dir), Some(name)) => dir.join(name),
        _ => path.to_path_buf(),
    }
}

/// Checks, before any work is done, that no two outputs of one command
/// name the same file (E0902): the second write would replace the first,
/// and two atomic writers racing for one name lose one of them. Each output
/// comes with the option that names it; `-` (standard output) is no file.
pub fn check_distinct(outputs: &[(&str, &Path)]) -> Result<(), Refused> {
    let files: Vec<(&str, &Path)> = outputs.iter().copied().filter(|(_, p)| p.as_os_str() != "-").collect();
    for (i, (flag_a, a)) in files.iter().enumerate() {
        for (flag_b, b) in &files[i + 1..] {
            let same = match (fs::metadata(a), fs::metadata(b)) {
                (Ok(ma), Ok(mb)) => same_file(&ma, &mb),
                _ => false,
            } || destination(a) == destination(b);
            if same {
                return Err(Refused {
                    code: Code::E0902,
                    message: format!(
                        "won't write `{}` for {flag_b}: {flag_a} writes the same file `{}`",
                        b.display(),
                        a.display()
                    ),
                });
            }
        }
    }
    Ok(())
}

/// An output written atomically: into a new temporary file beside `path`
/// (created exclusively, with an unpredictable name, so a link planted in
/// the directory can't redirect the write), renamed over `path` by
/// [`AtomicFile::commit`]. An existing `path` must be a regular file
/// (E0901) and keeps its permission bits (and, where allowed, its owner and
/// group); a new one gets 0666 less the umask, like any created file. If
/// the file is dropped without a commit, `path` is untouched and the
/// temporary file removed. Writes are buffered, so a long trace streams to
/// disk instead of growing in memory.
pub struct AtomicFile {
    path: std::path::PathBuf,
    existing: Option<Metadata>,
    tmp: io::BufWriter<tempfile::NamedTempFile>,
}

impl AtomicFile {
    pub fn create(path: &Path) -> Result<AtomicFile, Refused> {
        Self::open(path, false)
    }

    fn open(path: &Path, replacing_input: bool) -> Result<AtomicFile, Refused> {
        let existing = existing_output(path)?;
        if let Some(input) = existing.as_ref().and_then(|meta| read_as_input(path, meta)) {
            if !replacing_input {
                return Err(is_input(path, &input));
            }
        }
        let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("out");
        let prefix = format!(".{name}.");
        let mut builder = tempfile::Builder::new();
        builder.prefix(&prefix).suffix(".tmp").rand_bytes(12);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            builder.permissions(fs::Permissions::from_mode(0o666));
        }
        let tmp = builder.tempfile_in(dir).map_err(|e| cant_write(path, e))?;
        Ok(AtomicFile { path: path.to_path_buf(), existing, tmp: io::BufWriter::with_capacity(1 << 16, tmp) })
    }

    /// Flushes, syncs and renames the file into place.
    pub fn commit(self) -> Result<(), Refused> {
        let path = self.path;
        let tmp = self.tmp.into_inner().map_err(|e| cant_write(&path, e.error()))?;
        if let Some(meta) = &self.existing {
            keep_attributes(tmp.as_file(), meta).map_err(|e| cant_write(&path, e))?;
        }
        tmp.as_file().sync_all().map_err(|e| cant_write(&path, e))?;
        tmp.persist(&path).map_err(|e| cant_write(&path, e.error))?;
        Ok(())
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.tmp.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.tmp.flush()
    }
}

/// Writes `bytes` to `path` atomically (see [`AtomicFile`]).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Refused> {
    let mut file = AtomicFile::create(path)?;
    file.write_all(bytes).map_err(|e| cant_write(path, e))?;
    file.commit()
}

/// Replaces the input file `path`, read as `original`, by `bytes`: the one
/// command that rewrites its input is `linc fmt`, and it follows rustfmt's
/// rule (docs/style.md, "Writing the file"). A link or device is refused
/// (E0901), and so is a file its user can't write, or one that no one may
/// write (E0900): a read-only file is left as it is, even for root. A file
/// with one name is replaced atomically, as [`write_atomic`] writes; a file
/// with several (hard links) is written in place, once the new text is
/// whole, so that every name still shows the same file. If the file
/// changed since it was read (an editor saved it meanwhile), nothing is
/// written (E0900).
pub fn replace_input(path: &Path, original: &[u8], bytes: &[u8]) -> Result<(), Refused> {
    let Some(meta) = existing_output(path)? else {
        return Err(cant_write(path, "it is gone"));
    };
    if read_only(&meta) {
        return Err(cant_write(path, "it is read-only; `linc fmt` leaves it as it is"));
    }
    // Opened for writing (nothing changes yet) to learn whether we may.
    let mut file = fs::OpenOptions::new().read(true).write(true).open(path).map_err(|e| match e.kind() {
        io::ErrorKind::PermissionDenied => cant_write(path, format!("{e}; `linc fmt` leaves it as it is")),
        _ => cant_write(path, e),
    })?;
    let opened = file.metadata().map_err(|e| cant_write(path, e))?;
    if !same_file(&opened, &meta) {
        return Err(cant_write(path, "it was replaced while it was formatted"));
    }
    let mut now = Vec::with_capacity(original.len());
    (&mut file).take(MAX_INPUT_BYTES + 1).read_to_end(&mut now).map_err(|e| cant_write(path, e))?;
    if now != original {
        return Err(cant_write(path, "it changed while it was formatted"));
    }
    if links(&meta) > 1 {
        return write_in_place(&mut file, bytes).map_err(|e| cant_write(path, e));
    }
    drop(file);
    let mut atomic = AtomicFile::open(path, true)?;
    atomic.write_all(bytes).map_err(|e| cant_write(path, e))?;
    atomic.commit()
}

/// No write permission bit is set: the owner marked it read-only.
fn read_only(meta: &Metadata) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        meta.permissions().mode() & 0o222 == 0
    }
    #[cfg(not(unix))]
    {
        meta.permissions().readonly()
    }
}

/// How many names (hard links) the file has.
fn links(meta: &Metadata) -> u64 {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        meta.nlink()
    }
    #[cfg(not(unix))]
    {
        let _ = meta;
        1
    }
}

/// Overwrites an open file with `bytes` from its start, cuts what is left
/// of the old text, and syncs it.
fn write_in_place(file: &mut fs::File, bytes: &[u8]) -> io::Result<()> {
    use std::io::Seek;
    file.seek(io::SeekFrom::Start(0))?;
    file.write_all(bytes)?;
    file.set_len(bytes.len() as u64)?;
    file.sync_all()
}

/// Gives the new file the replaced file's permission bits (not set-id or
/// sticky bits, which a rewritten data file should not gain), then its
/// owner and group where the system allows it (root; or the group, for a
/// member), so that a shared file stays readable to the same people.
fn keep_attributes(file: &fs::File, old: &Metadata) -> io::Result<()> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::{MetadataExt, PermissionsExt};
        file.set_permissions(fs::Permissions::from_mode(old.mode() & 0o777))?;
        if std::os::unix::fs::fchown(file, Some(old.uid()), Some(old.gid())).is_err() {
            let _ = std::os::unix::fs::fchown(file, None, Some(old.gid()));
        }
        Ok(())
    }
    #[cfg(not(unix))]
    {
        file.set_permissions(old.permissions())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        linc_test_support::fresh_dir(&format!("files-{name}"))
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
    fn directories_are_not_inputs_or_outputs() {
        let dir = scratch("dirs");
        let e = read_input(&dir).expect_err("a directory");
        assert_eq!(e.to_string(), "it is a directory, not a regular file");
        assert_eq!(write_atomic(&dir, b"x").expect_err("a directory").code, "E0901");
    }

    #[test]
    fn a_failed_write_leaves_no_temporary_file() {
        let dir = scratch("failed");
        let out = dir.join("no-such-dir").join("out.sto");
        assert_eq!(write_atomic(&out, b"x").expect_err("no directory").code, "E0900");
        let good = dir.join("out.sto");
        write_atomic(&good, b"one").expect("write");
        write_atomic(&good, b"two").expect("rewrite");
        assert_eq!(fs::read(&good).expect("read"), b"two");
        let names: Vec<_> = fs::read_dir(&dir).expect("list").filter_map(|e| e.ok()).map(|e| e.file_name()).collect();
        assert_eq!(names, vec![std::ffi::OsString::from("out.sto")]);
    }

    #[cfg(unix)]
    #[test]
    fn replacing_an_input_keeps_hard_links_and_leaves_read_only_files() {
        use std::os::unix::fs::{MetadataExt, PermissionsExt};
        let dir = scratch("replace");
        let (a, b) = (dir.join("a.st"), dir.join("b.st"));
        fs::write(&a, b"old").expect("write");
        fs::hard_link(&a, &b).expect("link");
        replace_input(&a, b"old", b"new text").expect("in place");
        let (ma, mb) = (fs::metadata(&a).expect("a"), fs::metadata(&b).expect("b"));
        assert_eq!((ma.ino(), ma.nlink()), (mb.ino(), 2));
        assert_eq!(fs::read(&b).expect("read"), b"new text");
        replace_input(&a, b"new text", b"s").expect("shorter");
        assert_eq!(fs::read(&b).expect("read"), b"s", "the old text's tail is cut");
        let e = replace_input(&a, b"other", b"x").expect_err("changed since read");
        assert!(e.message.contains("changed while"), "{}", e.message);
        fs::set_permissions(&a, fs::Permissions::from_mode(0o444)).expect("chmod");
        let e = replace_input(&a, b"s", b"x").expect_err("read-only");
        assert_eq!((e.code.as_str(), fs::read(&a).expect("read")), ("E0900", b"s".to_vec()));
        assert!(e.message.contains("read-only"), "{}", e.message);
    }
}

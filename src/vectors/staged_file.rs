//! A file written front to back through an aligned staging buffer, its whole blocks sent to
//! the disk past the page cache (`O_DIRECT`, on Linux where the filesystem takes it).
//!
//! Why: a long vector dump written through the page cache costs the kernel a copy of every
//! byte into freshly allocated cache pages, on the same two cores that make and hash the
//! records (about a third of a dump's CPU time, measured with `perf`), and on a virtual
//! machine the first touch of those pages is slower still. Written from one reused buffer,
//! the bytes go to the device with no copy and no new pages. Only the file's last partial
//! block goes through the page cache, since a direct write must be whole aligned blocks.
//! A filesystem that refuses direct I/O (tmpfs, some network and FUSE filesystems) gets the
//! same bytes through the page cache instead.

use std::fs::File;
use std::io::{self, Write};
use std::path::Path;

/// Alignment of a direct write's buffer, offset and length (the largest logical block size
/// in common use).
const ALIGN: usize = 4096;
/// Bytes staged before a write: a whole number of `ALIGN` blocks.
pub const STAGE_BYTES: usize = 4 << 20;

pub struct StagedFile {
    /// The file, while no write of a whole stage is under way.
    out: Option<Out>,
    /// The stage being filled.
    stage: Stage,
    /// A whole stage being written on a thread of its own, so that the caller fills the next
    /// one meanwhile (a direct write waits for the device): the file and that stage come back
    /// when it is done.
    writing: Option<std::thread::JoinHandle<(Out, Stage, io::Result<()>)>>,
    /// The stage last written, to fill next.
    spare: Option<Stage>,
    /// A write has failed: every later call fails too, so no stage goes missing unseen.
    failed: bool,
}

/// The open file and how it is written.
struct Out {
    file: File,
    /// Whether whole blocks go past the page cache.
    direct: bool,
}

/// An aligned buffer of `STAGE_BYTES` and how much of it is filled.
struct Stage {
    /// `ALIGN` bytes more than a stage, so that an aligned stage lies inside it.
    buf: Vec<u8>,
    /// Where the aligned stage starts in `buf`.
    at: usize,
    len: usize,
}

impl Stage {
    fn new() -> Stage {
        let buf = vec![0u8; STAGE_BYTES + ALIGN];
        let at = buf.as_ptr().align_offset(ALIGN);
        Stage { buf, at, len: 0 }
    }

    fn filled(&self) -> &[u8] {
        &self.buf[self.at..self.at + self.len]
    }
}

impl Out {
    /// Write all of `b`: directly while the file is open so, and through the page cache from
    /// the first refusal on.
    fn write_all(&mut self, b: &[u8]) -> io::Result<()> {
        let mut done = 0;
        while done < b.len() {
            match self.file.write(&b[done..]) {
                Ok(0) => return Err(io::ErrorKind::WriteZero.into()),
                Ok(n) => done += n,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                // A filesystem that opens for direct I/O and then refuses the write itself,
                // or a short direct write that left the rest unaligned.
                Err(e) if self.direct && e.raw_os_error() == Some(libc::EINVAL) => self.stop_direct()?,
                Err(e) => return Err(e),
            }
        }
        Ok(())
    }

    fn stop_direct(&mut self) -> io::Result<()> {
        if self.direct {
            set_direct(&self.file, false)?;
            self.direct = false;
        }
        Ok(())
    }
}

impl StagedFile {
    /// Create (or truncate) `path`, for direct writes where the system takes them.
    pub fn create(path: &Path) -> io::Result<StagedFile> {
        StagedFile::create_as(path, true)
    }

    /// [`create`](Self::create), through the page cache unless `direct`.
    pub fn create_as(path: &Path, direct: bool) -> io::Result<StagedFile> {
        let (file, direct) = open(path, direct)?;
        Ok(StagedFile {
            out: Some(Out { file, direct }),
            stage: Stage::new(),
            writing: None,
            spare: None,
            failed: false,
        })
    }

    /// Whether whole blocks go to the disk past the page cache (after any write under way).
    pub fn direct(&mut self) -> io::Result<bool> {
        Ok(self.out()?.direct)
    }

    /// The file, once the write under way (if any) is done; its error, if it failed.
    fn out(&mut self) -> io::Result<&mut Out> {
        if self.failed {
            return Err(io::Error::other("an earlier write to this file failed"));
        }
        if let Some(w) = self.writing.take() {
            self.failed = true;
            let (out, stage, done) = w.join().map_err(|_| io::Error::other("the thread writing a stage panicked"))?;
            self.out = Some(out);
            // The written stage is the next one to fill after this.
            self.spare = Some(stage);
            done?;
            self.failed = false;
        }
        Ok(self.out.as_mut().expect("the file is back"))
    }

    /// The bytes written so far are in the file, the last partial block included, and on the
    /// disk: the file, for its caller to rename.
    pub fn finish(mut self) -> io::Result<File> {
        let tail = std::mem::replace(
            &mut self.stage,
            Stage {
                buf: Vec::new(),
                at: 0,
                len: 0,
            },
        );
        let out = self.out()?;
        if !tail.len.is_multiple_of(ALIGN) {
            out.stop_direct()?;
        }
        out.write_all(tail.filled())?;
        out.file.sync_all()?;
        Ok(self.out.take().expect("the file").file)
    }

    /// Send the full stage to the file on a thread, and go on filling another.
    fn write_stage(&mut self) -> io::Result<()> {
        self.out()?;
        let next = self.spare.take().unwrap_or_else(Stage::new);
        let mut stage = std::mem::replace(&mut self.stage, next);
        self.stage.len = 0;
        let mut out = self.out.take().expect("the file");
        self.writing = Some(std::thread::spawn(move || {
            let done = out.write_all(stage.filled());
            stage.len = 0;
            (out, stage, done)
        }));
        Ok(())
    }
}

impl Drop for StagedFile {
    fn drop(&mut self) {
        if let Some(w) = self.writing.take() {
            let _ = w.join();
        }
    }
}

impl Write for StagedFile {
    fn write(&mut self, b: &[u8]) -> io::Result<usize> {
        self.write_all(b)?;
        Ok(b.len())
    }

    fn write_all(&mut self, mut b: &[u8]) -> io::Result<()> {
        while !b.is_empty() {
            let (at, len) = (self.stage.at, self.stage.len);
            let n = b.len().min(STAGE_BYTES - len);
            self.stage.buf[at + len..at + len + n].copy_from_slice(&b[..n]);
            self.stage.len += n;
            b = &b[n..];
            if self.stage.len == STAGE_BYTES {
                self.write_stage()?;
            }
        }
        Ok(())
    }

    /// Staged bytes stay staged: a direct write must be a whole stage (see
    /// [`finish`](StagedFile::finish)).
    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

#[cfg(target_os = "linux")]
fn open(path: &Path, direct: bool) -> io::Result<(File, bool)> {
    use std::os::unix::fs::OpenOptionsExt;
    let mut o = std::fs::OpenOptions::new();
    o.write(true).create(true).truncate(true);
    if direct {
        match o.clone().custom_flags(libc::O_DIRECT).open(path) {
            Ok(f) => return Ok((f, true)),
            // The filesystem has no direct I/O: the page cache it is.
            Err(e) if e.raw_os_error() == Some(libc::EINVAL) => {}
            Err(e) => return Err(e),
        }
    }
    Ok((o.open(path)?, false))
}

#[cfg(not(target_os = "linux"))]
fn open(path: &Path, _direct: bool) -> io::Result<(File, bool)> {
    Ok((File::create(path)?, false))
}

#[cfg(target_os = "linux")]
fn set_direct(file: &File, on: bool) -> io::Result<()> {
    use std::os::fd::AsRawFd;
    let fd = file.as_raw_fd();
    // SAFETY: fcntl on a descriptor this `File` owns, with integer arguments only.
    let flags = unsafe { libc::fcntl(fd, libc::F_GETFL) };
    if flags < 0 {
        return Err(io::Error::last_os_error());
    }
    let flags = if on { flags | libc::O_DIRECT } else { flags & !libc::O_DIRECT };
    // SAFETY: as above.
    if unsafe { libc::fcntl(fd, libc::F_SETFL, flags) } < 0 {
        return Err(io::Error::last_os_error());
    }
    Ok(())
}

#[cfg(not(target_os = "linux"))]
fn set_direct(_file: &File, _on: bool) -> io::Result<()> {
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whatever the pieces (empty, smaller than a block, across stages, whole stages) and
    /// whichever way the file is written, it holds the bytes in order, its tail included.
    #[test]
    fn the_file_holds_every_byte_in_order() {
        let dir = tempfile::tempdir().unwrap();
        let mut rng = crate::vectors::rng::SplitMix64(0x57A6E);
        let sizes = [
            0,
            1,
            ALIGN - 1,
            ALIGN,
            ALIGN + 1,
            STAGE_BYTES - 3,
            STAGE_BYTES,
            STAGE_BYTES + 77,
            3 * STAGE_BYTES,
        ];
        for (i, &total) in sizes.iter().enumerate() {
            for direct in [true, false] {
                let data: Vec<u8> = (0..total).map(|_| rng.next_u64() as u8).collect();
                let path = dir.path().join(format!("f{i}_{direct}"));
                let mut f = StagedFile::create_as(&path, direct).unwrap();
                let mut rest = &data[..];
                while !rest.is_empty() {
                    let n = (rng.range(0, 3 * ALIGN as i64) as usize).min(rest.len());
                    f.write_all(&rest[..n]).unwrap();
                    rest = &rest[n..];
                }
                f.finish().unwrap();
                assert!(std::fs::read(&path).unwrap() == data, "{total} bytes, direct {direct}");
            }
        }
    }

    /// A direct write the system refuses (here a stage that is not aligned, as a filesystem
    /// that opens for direct I/O and refuses its writes answers) moves the file to the page
    /// cache and loses nothing.
    #[cfg(target_os = "linux")]
    #[test]
    fn a_refused_direct_write_goes_through_the_page_cache() {
        // The system's temporary folder, or the project's: one whose filesystem refuses an
        // unaligned direct write (ext4, xfs); tmpfs and btrfs take it through the page cache.
        let refuses = |d: &Path| {
            let (mut f, direct) = open(&d.join("probe"), true).unwrap();
            direct && f.write(&[0u8; 1]).is_err_and(|e| e.raw_os_error() == Some(libc::EINVAL))
        };
        let dirs: Vec<_> = [std::env::temp_dir(), env!("CARGO_MANIFEST_DIR").into()]
            .into_iter()
            .map(|d| tempfile::tempdir_in(d).unwrap())
            .collect();
        let found = dirs.iter().find(|d| refuses(d.path()));
        // Where no filesystem here refuses, the bytes must still come out whole; the fallback
        // itself is then not reached, and the test says so.
        let dir = found.unwrap_or_else(|| {
            eprintln!("no folder here refuses an unaligned direct write: the fallback is not exercised");
            &dirs[0]
        });
        let path = dir.path().join("f");
        let mut f = StagedFile::create_as(&path, true).unwrap();
        f.stage.at += 1;
        let data: Vec<u8> = (0..2 * STAGE_BYTES + 5).map(|i| (i * 7 % 251) as u8).collect();
        f.write_all(&data[..STAGE_BYTES]).unwrap();
        if found.is_some() {
            assert!(!f.direct().unwrap(), "the unaligned write was refused");
        }
        f.write_all(&data[STAGE_BYTES..]).unwrap();
        f.finish().unwrap();
        assert!(std::fs::read(&path).unwrap() == data);
    }
}

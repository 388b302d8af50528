//! Writing images: PNG through a temporary file and a rename, so a failed or interrupted
//! write never leaves a partial image behind; and the difference heat map.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// Write `bytes` to `path` atomically (temporary sibling, then rename).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let _cleanup = crate::interrupt::cleanup();
    crate::interrupt::check()?;
    // A symbolic link keeps pointing where it did: the file it leads to is replaced.
    let target = link_target(path)?;
    let path = target.as_path();
    crate::limits::check_not_input(path)?;
    // A device or FIFO (e.g. /dev/full, /dev/stdout) is written in place: renaming over it
    // would replace the device node.
    if let Ok(meta) = std::fs::metadata(path) {
        if !meta.is_file() {
            if meta.is_dir() {
                return Err(folder_in_the_way(path));
            }
            return std::fs::write(path, bytes).map_err(|e| Error::io(path, e));
        }
    }
    let (dir, tmp) = temp_beside(path)?;
    let res = std::fs::write(&tmp, bytes).and_then(|_| {
        // Inside `commit::together` the rename waits for the other results.
        if crate::commit::defer(&tmp, path) {
            Ok(())
        } else {
            std::fs::rename(&tmp, path)
        }
    });
    if let Err(e) = res {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::io(path, e));
    }
    // What a killed run left in this folder goes now that a run has written there.
    crate::temp_files::clean_stale(&dir, 0);
    Ok(())
}

/// Where a result file streamed to its own temporary name (a vector set's) goes: the end of
/// `path`'s symbolic links, refused as `write_atomic` refuses it when that is an input of
/// the run or a folder.
pub fn streamed_result_path(path: &Path) -> Result<PathBuf> {
    let target = link_target(path)?;
    crate::limits::check_not_input(&target)?;
    if target.is_dir() {
        return Err(folder_in_the_way(&target));
    }
    Ok(target)
}

/// The refusal of a result file whose path is a folder.
fn folder_in_the_way(path: &Path) -> Error {
    Error::Other(format!(
        "{}: is a folder, where this run writes a file\n  fix: move the folder away, or give the output another path (folder)",
        path.display()
    ))
}

/// The folder of result file `path`, made as every command's output folder is, and the
/// temporary name beside it that a write goes to before its rename (the pattern
/// `temp_files::clean_stale` clears after a killed run).
fn temp_beside(path: &Path) -> Result<(std::path::PathBuf, std::path::PathBuf)> {
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .ok_or_else(|| Error::Other(format!("{}: not a file path", path.display())))?;
    make_folder(dir)?;
    Ok((dir.to_path_buf(), crate::temp_files::hidden_temp_path(&dir.join(name))))
}

/// Where an output path really leads: `path` itself, or the file at the end of its chain of
/// symbolic links (which need not exist yet), so a result written through a link replaces the
/// link's target and the link stays.
pub fn link_target(path: &Path) -> Result<std::path::PathBuf> {
    let mut at = path.to_path_buf();
    // As many hops as the kernel follows before it calls a chain a loop.
    for hop in 0..40 {
        match std::fs::symlink_metadata(&at) {
            Ok(m) if m.file_type().is_symlink() => {
                let next = std::fs::read_link(&at).map_err(|e| Error::io(&at, e))?;
                at = match at.parent() {
                    Some(dir) if next.is_relative() => dir.join(next),
                    _ => next,
                };
            }
            _ => {
                // A link is written through, never used to make folders: a dangling link's
                // target folder is the link maker's to create (a link to /nonexistent/x must
                // not create /nonexistent).
                let dir = at.parent().filter(|d| !d.as_os_str().is_empty());
                if hop > 0 && dir.is_some_and(|d| !d.is_dir()) {
                    return Err(Error::Other(format!(
                        "{}: a symbolic link to {}, whose folder does not exist\n  fix: create {}, point the link at a file in a folder that exists, or remove the link",
                        path.display(),
                        at.display(),
                        dir.expect("checked").display()
                    )));
                }
                return Ok(at);
            }
        }
    }
    Err(Error::Other(format!(
        "{}: a loop of symbolic links (40 hops without reaching a file)\n  fix: point the link at a file, or give the output another path",
        path.display()
    )))
}

/// Check before a long run that its result file `path` can be written at the end: not a
/// folder, not an input, and its folder made and writable (a file is created there and
/// removed). The run's hours are not spent on a result that cannot land.
pub fn check_writable(path: &Path) -> Result<()> {
    let target = link_target(path)?;
    let path = target.as_path();
    crate::limits::check_not_input(path)?;
    if path.is_dir() {
        return Err(folder_in_the_way(path));
    }
    let (_, tmp) = temp_beside(path)?;
    std::fs::write(&tmp, b"").map_err(|e| {
        Error::Other(format!(
            "{}: this run could not write its result here ({e})\n  fix: give a path in a folder you can write to",
            path.display()
        ))
    })?;
    let _ = std::fs::remove_file(&tmp);
    Ok(())
}

/// Run `f`, which writes into `dir`; if it fails, remove every entry it added to `dir`, so a
/// failure midway (a second set, a full disk) leaves nothing that looks like a result.
pub fn undo_on_error<T>(dir: &Path, f: impl FnOnce() -> Result<T>) -> Result<T> {
    let _cleanup = crate::interrupt::cleanup();
    let list = || -> std::collections::BTreeSet<std::ffi::OsString> {
        std::fs::read_dir(dir)
            .map(|d| d.filter_map(|e| e.ok().map(|e| e.file_name())).collect())
            .unwrap_or_default()
    };
    let before = list();
    let existed = dir.exists();
    let r = f();
    if r.is_err() {
        for name in list().difference(&before) {
            let _ = std::fs::remove_file(dir.join(name));
        }
        if !existed {
            let _ = std::fs::remove_dir(dir);
        }
    }
    r
}

/// Encode 8-bit RGB pixels as PNG.
pub fn encode_png(w: u32, h: u32, rgb: &[[u8; 3]]) -> Result<Vec<u8>> {
    use image::ImageEncoder;
    let mut buf = Vec::new();
    let flat: Vec<u8> = rgb.iter().flatten().copied().collect();
    image::codecs::png::PngEncoder::new(&mut buf)
        .write_image(&flat, w, h, image::ExtendedColorType::Rgb8)
        .map_err(|e| Error::Other(format!("PNG encoding failed: {e}")))?;
    Ok(buf)
}

/// Encode 8-bit RGB pixels as PNG and write atomically.
pub fn write_png(path: &Path, w: u32, h: u32, rgb: &[[u8; 3]]) -> Result<()> {
    write_atomic(path, &encode_png(w, h, rgb)?)
}

/// Colour codes (0..=max) to 8-bit.
pub fn codes_to_u8(c: &[[u32; 3]], max: u32) -> Vec<[u8; 3]> {
    c.iter()
        .map(|p| p.map(|x| ((x as u64 * 255 + max as u64 / 2) / max as u64) as u8))
        .collect()
}

/// [0,1] colours to 8-bit.
pub fn f64_to_u8(c: &[[f64; 3]]) -> Vec<[u8; 3]> {
    c.iter().map(|p| p.map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8)).collect()
}

/// Heat map of per-pixel error (largest channel, in LSBs): black at 0, through blue, red and
/// yellow to white at `scale` LSBs and above.
pub fn heat_map(err_lsb: &[f64], scale: f64) -> Vec<[u8; 3]> {
    const STOPS: [[f64; 3]; 5] = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 1.0, 1.0]];
    err_lsb
        .iter()
        .map(|e| {
            let t = (e / scale.max(1e-9)).clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
            let i = (t.floor() as usize).min(STOPS.len() - 2);
            let f = t - i as f64;
            [0, 1, 2].map(|c| ((STOPS[i][c] * (1.0 - f) + STOPS[i + 1][c] * f) * 255.0).round() as u8)
        })
        .collect()
}

/// [0,1] colours to codes, rounded to nearest.
pub fn quantise(c: &[[f64; 3]], max: u32) -> Vec<[u32; 3]> {
    c.iter()
        .map(|p| p.map(|x| (x.clamp(0.0, 1.0) * max as f64).round() as u32))
        .collect()
}

/// Folders [`make_folder`] made in this run.
static MADE: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// Remove the folders this run made that are still empty, the deepest first: a run that
/// fails (a file path past the system's limit under a new folder, say) leaves no empty
/// folders behind. A folder that holds nothing but files named in `own` (the run's own
/// bookkeeping, such as its work lock) counts as empty; one with anything else in it stays.
pub fn remove_made_folders(own: &[&str]) {
    let made = std::mem::take(&mut *MADE.lock().unwrap_or_else(|p| p.into_inner()));
    remove_folders(made, own);
}

/// [`remove_made_folders`] from a path that may have stopped another thread while it held
/// the list (out of memory): a list that stays held is left as it is.
pub fn remove_made_folders_unless_held(own: &[&str]) {
    if let Some(mut g) = crate::temp_files::lock_unless_held(&MADE) {
        remove_folders(std::mem::take(&mut *g), own);
    }
}

fn remove_folders(mut made: Vec<std::path::PathBuf>, own: &[&str]) {
    made.sort_by_key(|p| std::cmp::Reverse(p.components().count()));
    for d in made {
        let names: Vec<_> = std::fs::read_dir(&d)
            .into_iter()
            .flatten()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        if names.iter().all(|n| own.iter().any(|o| n == *o)) {
            for n in &names {
                let _ = std::fs::remove_file(d.join(n));
            }
        }
        let _ = std::fs::remove_dir(d);
    }
}

/// Make output folder `dir` and its parents, or say which part could not be made and why
/// (`--out /proc/x` reads as "no such file" in the OS's words). The folders it makes are
/// recorded for [`remove_made_folders`].
pub fn make_folder(dir: &Path) -> Result<()> {
    if let (Ok(m), Err(e)) = (std::fs::symlink_metadata(dir), std::fs::metadata(dir)) {
        if m.file_type().is_symlink() {
            let to = std::fs::read_link(dir).map(|t| t.display().to_string()).unwrap_or_default();
            return Err(match e.kind() {
                std::io::ErrorKind::NotFound => Error::Other(format!(
                    "{}: a symbolic link to {to}, which does not exist\n  fix: create {to}, or remove the link",
                    dir.display()
                )),
                // ELOOP: the chain comes back to itself (a -> b -> a); nothing at its end to create.
                _ if e.raw_os_error() == Some(libc::ELOOP) => Error::Other(format!(
                    "{}: a loop of symbolic links (it leads to {to}, which leads back)\n  fix: point the link at a folder, or give the output another path",
                    dir.display()
                )),
                _ => Error::io(dir, e),
            });
        }
    }
    // Below the deepest folder that was there before, every one is this call's.
    let before = dir
        .ancestors()
        .find(|a| a.as_os_str().is_empty() || a.exists())
        .map(Path::to_path_buf);
    let made = dir.ancestors().take_while(|a| Some(*a) != before.as_deref());
    if let Err(e) = std::fs::create_dir_all(dir) {
        // A path past the system's length limit fails many folders down: this call's go now.
        for d in made {
            let _ = std::fs::remove_dir(d);
        }
        return Err(not_made(dir, e));
    }
    MADE.lock().unwrap_or_else(|p| p.into_inner()).extend(made.map(Path::to_path_buf));
    Ok(())
}

/// Why `dir` could not be made, named at its deepest part that exists.
fn not_made(dir: &Path, e: std::io::Error) -> Error {
    let existing = dir.ancestors().skip(1).find(|a| a.as_os_str().is_empty() || a.exists());
    let at = existing.map_or(".".into(), |a| {
        if a.as_os_str().is_empty() {
            ".".into()
        } else {
            a.display().to_string()
        }
    });
    Error::Other(format!(
        "{}: cannot create this folder in {at} ({e})\n  fix: give an output folder under one you can write to",
        dir.display()
    ))
}

/// Write every file into `dir` as one (`commit::together`): on any failure the folder keeps
/// what it held before, the files this call would have replaced included.
pub fn write_files<T: AsRef<[u8]>>(dir: &Path, files: &[(String, T)]) -> Result<()> {
    make_folder(dir)?;
    crate::commit::together(|| {
        files
            .iter()
            .try_for_each(|(name, text)| write_atomic(&dir.join(name), text.as_ref()))
    })
}

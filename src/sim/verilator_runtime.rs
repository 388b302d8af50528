//! Verilator's runtime (`verilated.o`, `verilated_threads.o`, `verilated_timing.o`, …) is
//! the same C++ compiled the same way in every build of one mode (binary or harness, traced or
//! not, one optimisation level), yet its makefile compiles it again each time: about 4 CPU
//! seconds of a small top's 6. Each runtime object is kept in the shared cache
//! (`cache::shared_root`) under a key made of its exact compile command and the versions of
//! Verilator and the compiler, and copied into a build's object folder before `make` runs, so
//! make finds it newer than its source and compiles only the design. The key is the command
//! make would run, read with `make -n`, so a flag that changes the object changes the key.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Mutex;

/// One runtime object the build's makefile would compile: its name in the object folder and
/// the folder of the shared cache it is kept in.
pub struct RuntimeObject {
    pub name: String,
    entry: PathBuf,
}

/// The runtime objects `make -n -f MK ARGS` (run in `obj`) would compile, keyed, when a
/// shared cache exists; none otherwise (the build compiles them as before).
pub fn runtime_objects(obj: &Path, mk: &str, make_args: &[String]) -> Result<Vec<RuntimeObject>> {
    let Some(root) = crate::cache::shared_root() else {
        return Ok(Vec::new());
    };
    let out = crate::tool::output(Command::new("make").args(["-n", "-f", mk]).args(make_args).current_dir(obj))
        .map_err(|e| Error::Other(format!("make -n in {}: {e}", obj.display())))?;
    if !out.status.success() {
        // The real make reports the problem with its own words.
        return Ok(Vec::new());
    }
    Ok(compile_lines(&String::from_utf8_lossy(&out.stdout))
        .into_iter()
        .map(|(name, compiler, line)| {
            let mut k = crate::cache::Key::new("verilator_runtime");
            k.add(line.as_bytes()).add_tool("verilator").add_tool(&compiler);
            RuntimeObject {
                entry: root.join(format!("verilator_runtime_{}", k.finish())),
                name,
            }
        })
        .collect())
}

/// (object, compiler, command) of every line of a dry run that compiles one of Verilator's
/// own sources (`-c -o verilated….o …/verilated….cpp`).
fn compile_lines(dry_run: &str) -> Vec<(String, String, String)> {
    dry_run
        .lines()
        .filter_map(|line| {
            let w: Vec<&str> = line.split_whitespace().collect();
            let o = w.iter().position(|x| *x == "-o").and_then(|i| w.get(i + 1))?;
            let src = Path::new(w.last()?);
            let stem = src.file_stem()?.to_str()?;
            let ours = w.contains(&"-c")
                && stem.starts_with("verilated")
                && src.extension().is_some_and(|e| e == "cpp")
                && *o == format!("{stem}.o");
            ours.then(|| (o.to_string(), w[0].to_string(), line.trim().to_string()))
        })
        .collect()
}

impl RuntimeObject {
    /// Drop this object from `obj` and its entry from the cache, so the next make compiles it
    /// and the build stores it afresh.
    pub fn forget(&self, obj: &Path) {
        let _ = std::fs::remove_file(obj.join(&self.name));
        let _ = std::fs::remove_dir_all(&self.entry);
    }
}

/// Copy every kept object into `obj`; returns the ones the cache did not hold.
pub fn fetch<'a>(objects: &'a [RuntimeObject], obj: &Path) -> Vec<&'a RuntimeObject> {
    objects
        .iter()
        .filter(|o| {
            let kept = crate::cache::is_complete(&o.entry, &[&o.name]) && std::fs::copy(o.entry.join(&o.name), obj.join(&o.name)).is_ok();
            !kept
        })
        .collect()
}

/// Keep the objects a build compiled (a failure to keep one only costs a later build time).
pub fn store(missing: &[&RuntimeObject], obj: &Path) {
    // Two builds of one process share the temporary name of an entry.
    static STORING: Mutex<()> = Mutex::new(());
    let _one = STORING.lock().unwrap_or_else(|e| e.into_inner());
    for o in missing {
        let from = obj.join(&o.name);
        let _ = crate::cache::build_dir(&o.entry, &[&o.name], |tmp| {
            std::fs::copy(&from, tmp.join(&o.name)).map(|_| ()).map_err(|e| Error::io(&from, e))
        });
    }
}

/// The build folder's `RUNTIME_RECORD`: each runtime object, and whether it was taken from
/// the cache or compiled (none listed: no shared cache).
pub fn record(dir: &Path, objects: &[RuntimeObject], missing: &[&RuntimeObject]) -> Result<()> {
    let mut s = String::new();
    for o in objects {
        let how = if missing.iter().any(|m| m.name == o.name) {
            "compiled"
        } else {
            "cached"
        };
        s += &format!("{} {how} {}\n", o.name, o.entry.display());
    }
    let f = dir.join(RUNTIME_RECORD);
    std::fs::write(&f, s).map_err(|e| Error::io(&f, e))
}

/// The file in a Verilator build folder that says where its runtime objects came from.
pub const RUNTIME_RECORD: &str = "verilator_runtime.txt";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_verilators_own_sources_are_taken_from_a_dry_run() {
        let dry =
            "g++  -I.  -MMD -I/usr/share/verilator/include -DVM_TRACE=0 -O1 -c -o verilated.o /usr/share/verilator/include/verilated.cpp\n\
                   g++  -I.  -MMD -O1 -c -o Vtb_top__ALL.o Vtb_top__ALL.cpp\n\
                   g++ -O1 -c -o verilated_threads.o /usr/share/verilator/include/verilated_threads.cpp\n\
                   g++ -O1 -c -o harness.o ../harness.cpp\n\
                   g++    verilated.o Vtb_top__ALL.a -pthread -o ../tb\n";
        let got = compile_lines(dry);
        let names: Vec<&str> = got.iter().map(|g| g.0.as_str()).collect();
        assert_eq!(names, ["verilated.o", "verilated_threads.o"]);
        assert!(got.iter().all(|g| g.1 == "g++"));
        // The key holds the whole command: another define is another object.
        assert!(got[0].2.contains("-DVM_TRACE=0"));
    }
}

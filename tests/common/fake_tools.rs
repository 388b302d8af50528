//! Fake tools on PATH, for tests of how gbump takes a tool's misbehaviour: an Icarus whose
//! `iverilog` "compiles" (writes its `-o` file) and whose `vvp` runs a given shell body, or
//! any one tool that runs a given body.

// Each test binary includes this file and uses some of it.
#![allow(dead_code)]

use std::path::Path;

/// Write `name` into `bin` (created) running `body` after `#!/bin/sh`; the PATH to run gbump
/// with: `bin` first.
pub fn tool(bin: &Path, name: &str, body: &str) -> String {
    std::fs::create_dir_all(bin).unwrap();
    let p = bin.join(name);
    std::fs::write(&p, format!("#!/bin/sh\n{body}\n")).unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o755)).unwrap();
    format!("{}:{}", bin.display(), std::env::var("PATH").unwrap())
}

/// An Icarus in `bin` whose `vvp` runs `vvp_body`; the PATH to run gbump with.
pub fn icarus(bin: &Path, vvp_body: &str) -> String {
    tool(
        bin,
        "iverilog",
        "while [ $# -gt 0 ]; do if [ \"$1\" = -o ]; then shift; echo fake-image > \"$1\"; fi; shift; done\nexit 0",
    );
    tool(bin, "vvp", vvp_body)
}

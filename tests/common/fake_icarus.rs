//! A fake Icarus on PATH: an `iverilog` that "compiles" (writes its `-o` file) and a `vvp`
//! that runs a given shell body, for tests of how gbump takes a simulator's misbehaviour.

// Each test binary includes this file.
#![allow(dead_code)]

use std::path::Path;

/// Write the two tools into `bin` (created); `vvp` runs `vvp_body` after `#!/bin/sh`. The
/// PATH to run gbump with: `bin` first.
pub fn install(bin: &Path, vvp_body: &str) -> String {
    std::fs::create_dir_all(bin).unwrap();
    let iverilog = "#!/bin/sh\nwhile [ $# -gt 0 ]; do if [ \"$1\" = -o ]; then shift; echo fake-image > \"$1\"; fi; shift; done\nexit 0\n";
    let vvp = format!("#!/bin/sh\n{vvp_body}\n");
    for (n, t) in [("iverilog", iverilog.to_string()), ("vvp", vvp)] {
        let p = bin.join(n);
        std::fs::write(&p, t).unwrap();
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    format!("{}:{}", bin.display(), std::env::var("PATH").unwrap())
}

//! The SystemVerilog package `gbump_dpi_pkg` (`include/gbump_dpi_pkg.sv`): one
//! `import "DPI-C"` declaration per function of the C header, derived from the header text
//! itself (which cbindgen writes from `ffi.rs`), so the three cannot disagree.
//!
//! Each C type maps to the SystemVerilog type whose DPI-C representation it is: handles to
//! `chandle`, `const char *` to `string`, `int32_t` to `int`, 64-bit integers to `longint`,
//! a record buffer (`const uint32_t *` / `uint32_t *`) to an input / output
//! `bit [GBUMP_MAX_BITS-1:0]` (`svBitVecVal *`, 32-bit words LSB first), `int32_t *` to
//! `output int`. Functions named `*_batch` take arrays of records, and those taking a
//! `const uint64_t *` arrays of words: they are C-only.

use crate::error::{Error, Result};

/// One function of the header.
#[derive(Clone, Debug, PartialEq)]
pub struct CFn {
    pub name: String,
    pub ret: String,
    /// (type, name) of each argument.
    pub args: Vec<(String, String)>,
    /// The first paragraph of its doc comment, on one line.
    pub doc: String,
}

/// Split `type name` (the name is the trailing identifier; `*` belongs to the type).
fn split_decl(d: &str) -> Option<(String, String)> {
    let d = d.trim();
    let start = d.rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))? + 1;
    let (ty, name) = d.split_at(start);
    (!name.is_empty() && !ty.trim().is_empty()).then(|| {
        (
            ty.split_whitespace()
                .collect::<Vec<_>>()
                .join(" ")
                .replace(" *", "*")
                .replace('*', " *"),
            name.to_string(),
        )
    })
}

/// The function prototypes of a C header, with the first line of the doc comment above each.
pub fn functions(header: &str) -> Result<Vec<CFn>> {
    let mut out = Vec::new();
    let mut doc = String::new();
    let mut stmt = String::new();
    let mut in_comment = false;
    let mut para_done = false;
    for line in header.lines() {
        let t = line.trim();
        if in_comment {
            let body = t.trim_start_matches('*').trim();
            if t.starts_with("*/") || t.ends_with("*/") {
                in_comment = false;
            } else if body.is_empty() {
                para_done = true;
            } else if !para_done {
                // The first paragraph of the doc comment, one line.
                doc = format!("{doc} {body}").trim().to_string();
            }
            continue;
        }
        if t.starts_with("/*") {
            in_comment = !t.ends_with("*/");
            doc.clear();
            para_done = false;
            if !in_comment {
                doc = t
                    .trim_start_matches("/*")
                    .trim_end_matches("*/")
                    .trim_start_matches('*')
                    .trim()
                    .to_string();
            }
            continue;
        }
        if t.is_empty()
            || t.starts_with('#')
            || t.starts_with("//")
            || t.starts_with("typedef")
            || t == "}"
            || t.starts_with("extern \"C\"")
        {
            continue;
        }
        stmt.push(' ');
        stmt.push_str(t);
        if !t.ends_with(';') {
            continue;
        }
        let s = std::mem::take(&mut stmt);
        let bad = || {
            Error::Other(format!(
                "C header: cannot read the declaration `{}`\n  fix: keep ffi.rs to plain functions of the types dpi_pkg.rs maps",
                s.trim()
            ))
        };
        let (head, rest) = s.split_once('(').ok_or_else(bad)?;
        let (ret, name) = split_decl(head).ok_or_else(bad)?;
        let args_text = rest.trim_end_matches(';').trim().strip_suffix(')').ok_or_else(bad)?;
        let args = if args_text.trim() == "void" {
            Vec::new()
        } else {
            args_text.split(',').map(|a| split_decl(a).ok_or_else(bad)).collect::<Result<_>>()?
        };
        out.push(CFn {
            name,
            ret,
            args,
            doc: std::mem::take(&mut doc),
        });
    }
    Ok(out)
}

/// `text` in lines of at most `width` characters (longer words stay whole).
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for w in text.split_whitespace() {
        match lines.last_mut() {
            Some(l) if l.len() + 1 + w.len() <= width => {
                l.push(' ');
                l.push_str(w);
            }
            _ => lines.push(w.to_string()),
        }
    }
    lines
}

/// The SystemVerilog type of a C return type, or of an argument (with its direction).
fn sv_type(c: &str, arg: bool) -> Option<String> {
    let handle = c.trim_start_matches("const ").trim_start_matches("struct ").starts_with("Gbump") && c.ends_with(" *");
    Some(
        match c {
            "void" if !arg => "void",
            "int32_t" => "int",
            "int64_t" | "uint64_t" => "longint",
            "const char *" => "string",
            "const uint32_t *" if arg => "input gbump_record_t",
            "uint32_t *" if arg => "output gbump_record_t",
            "int32_t *" if arg => "output int",
            _ if handle => "chandle",
            _ => return None,
        }
        .to_string(),
    )
    .map(|t| {
        if arg && !t.starts_with("input") && !t.starts_with("output") {
            format!("input {t}")
        } else {
            t
        }
    })
}

/// The string functions that never give NULL (static strings, and the last error, which is
/// "" before any failure).
const NEVER_NULL: &[&str] = &["gbump_version", "gbump_source", "gbump_last_error"];

/// Whether `f` is declared in the package: functions of arrays (of records, `*_batch`, or of
/// 64-bit words) are C-only; a testbench takes them an element at a time.
pub fn is_dpi(f: &CFn) -> bool {
    !f.name.ends_with("_batch") && !f.args.iter().any(|(t, _)| t == "const uint64_t *")
}

/// The package text for the functions of `header`.
pub fn package(header: &str, regenerate: &str) -> Result<String> {
    let fns = functions(header)?;
    if fns.is_empty() {
        return Err(Error::Other(
            "C header: no functions found\n  fix: regenerate include/gbump.h".into(),
        ));
    }
    let mut s = format!(
        "// Generated by {} - do not edit.\n// Regenerate: {regenerate}\n// SystemVerilog DPI-C declarations of the gbump golden model (include/gbump.h); link\n// libgbump (Verilator: -LDFLAGS /path/to/libgbump.so; Icarus has no DPI-C). Records are\n// packed LSB first, as in the vector files; C-only functions (arrays of records or words):{}\n// A string that fails is \"\" here (NULL in C), and a record output is zero above the\n// record: those functions bind the library's gbump_dpi_* symbols, not in the C header. A C++\n// file that includes gbump.h must not also include Verilator's V*__Dpi.h (the two declare\n// the same functions with different handle types): call the library from one or the other.\n",
        crate::TOOL,
        fns.iter().filter(|f| !is_dpi(f)).map(|f| format!(" {}", f.name)).collect::<String>()
    );
    // The generated RTL's timescale: a file list that names the package first, as packages
    // come before their users, then builds under Verilator without TIMESCALEMOD.
    s += "`timescale 1ns / 1ps\n";
    s += "package gbump_dpi_pkg;\n";
    // A package a testbench imports for its functions leaves this parameter unread, which
    // `-Wall` would fail.
    s += &format!(
        "    /* verilator lint_off UNUSEDPARAM */\n    localparam int GBUMP_ABI_VERSION = {};\n    /* verilator lint_on UNUSEDPARAM */\n",
        super::ABI_VERSION
    );
    s += &format!(
        "    // Width of the record vectors: every configuration's records fit.\n    localparam int GBUMP_MAX_BITS = {};\n",
        super::MAX_RECORD_BITS
    );
    s += "    typedef bit [GBUMP_MAX_BITS-1:0] gbump_record_t;\n";
    for f in fns.iter().filter(|f| is_dpi(f)) {
        let unmapped = |t: &str| {
            Error::Other(format!(
                "C header: {}: type `{t}` has no DPI-C mapping\n  fix: use a type src/capi/dpi_pkg.rs maps, or name the function *_batch to keep it C-only",
                f.name
            ))
        };
        let ret = sv_type(&f.ret, false).ok_or_else(|| unmapped(&f.ret))?;
        let args = f
            .args
            .iter()
            .map(|(t, n)| sv_type(t, true).map(|t| format!("{t} {n}")).ok_or_else(|| unmapped(t)))
            .collect::<Result<Vec<_>>>()?;
        // A string that may be NULL, or a record written in part, binds its DPI-C form.
        let wrapped = super::dpi::WRAPPED.iter().find(|w| w.0 == f.name).map(|w| w.1);
        let needs_wrapper =
            (f.ret == "const char *" && !NEVER_NULL.contains(&f.name.as_str())) || f.args.iter().any(|(t, _)| t == "uint32_t *");
        if needs_wrapper != wrapped.is_some() {
            return Err(Error::Other(format!(
                "C header: {}: {}\n  fix: list it in src/capi/dpi.rs's wrappers exactly when it returns a string that may be NULL or writes a record",
                f.name,
                if needs_wrapper { "has no DPI-C form" } else { "has a DPI-C form it does not need" }
            )));
        }
        let mut doc = f.doc.clone();
        if wrapped.is_some() {
            doc += if f.ret == "const char *" {
                " Under DPI-C: \"\" where C gives NULL (gbump_last_error() says why)."
            } else {
                " Under DPI-C: the whole vector is written, zero above the record."
            };
        }
        for line in wrap(&doc, 92) {
            s += &format!("    // {line}\n");
        }
        let bind = wrapped.map(|w| format!("{w} = ")).unwrap_or_default();
        s += &format!("    import \"DPI-C\" {bind}function {ret} {}({});\n", f.name, args.join(", "));
    }
    s += "endpackage\n";
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_prototypes_and_maps_types() {
        let h = "#include <stdint.h>\ntypedef struct GbumpConfig GbumpConfig;\n/**\n * Evaluate.\n * More.\n */\nint32_t gbump_eval(const GbumpConfig *h,\n                   const char *target,\n                   const uint32_t *rec_in,\n                   uint32_t *rec_out);\n\nconst char *gbump_version(void);\nint32_t gbump_eval_batch(const GbumpConfig *h, const uint32_t *a, uint32_t *b, int64_t count);\n";
        let f = functions(h).unwrap();
        assert_eq!(f.len(), 3);
        assert_eq!(f[0].doc, "Evaluate. More.");
        assert_eq!(f[1].ret, "const char *");
        let p = package(h, "x").unwrap();
        assert!(p.contains("import \"DPI-C\" gbump_dpi_eval = function int gbump_eval(input chandle h, input string target, input gbump_record_t rec_in, output gbump_record_t rec_out);"), "{p}");
        assert!(p.contains("import \"DPI-C\" function string gbump_version();"));
        assert!(!p.contains("function int gbump_eval_batch"));
        assert!(package("float f(double x);", "x").is_err());
        // A string function that may fail, without its DPI-C form, is refused.
        assert!(package("const char *gbump_new_name(const GbumpConfig *h);", "x")
            .unwrap_err()
            .to_string()
            .contains("has no DPI-C form"));
    }
}

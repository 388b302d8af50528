"""The Python module against the files gbump writes: the same records, ROM words and interface.

    python3 check_module.py GBUMP_EXE WORK_DIR [CONFIG.toml]

runs `gbump rtl`, `gbump vectors` and `gbump rom` into WORK_DIR and checks that the module
gives the same bytes: vector sets (random, corners, exhaustive), evaluation of every record
of a top and a unit set with its expected columns cleared, the stimulus stream, the per-field
form, the power table and the interface JSON; and that bad input raises GbumpError with the
library's message. Prints `N passed, 0 failed` and exits 0 when all hold.
"""

import json
import os
import subprocess
import sys

import numpy as np

import gbump

exe, work = sys.argv[1], sys.argv[2]
config = sys.argv[3] if len(sys.argv) > 3 else None
cfg_args = ["--config", config] if config else []
passed = 0


def check(cond, what):
    global passed
    if not cond:
        sys.exit(f"FAILED: {what}")
    passed += 1


# A module built from other sources than the gbump under test would compare two different
# programs: say so first, with the fix, rather than fail on whatever differs.
version = subprocess.run([exe, "--version"], check=True, capture_output=True, text=True).stdout
if f"(source {gbump.__source__})" not in version:
    sys.exit(
        f"FAILED: the installed module was built from other sources (source {gbump.__source__}) than {exe} ({version.strip()})\n"
        "  fix: rebuild and install it: scripts/python-module.sh"
    )
passed += 1


def run(*args):
    subprocess.run([exe, *args, *cfg_args], check=True, stdout=subprocess.DEVNULL)


def hex_words(path):
    with open(path) as f:
        return [int(w, 16) for w in (line.split("//", 1)[0].strip() for line in f) if w]


def rows_from_hex(path, words):
    """A vector file's records as uint32 rows, words LSB first."""
    recs = hex_words(path)
    return np.array([[(r >> (32 * i)) & 0xFFFFFFFF for i in range(words)] for r in recs], dtype=np.uint32).reshape(len(recs), words)


def cleared(model, target, rows):
    """`rows` with every expected column zeroed: what a testbench knows before the model."""
    out = rows.copy()
    ints = [int.from_bytes(r.astype("<u4").tobytes(), "little") for r in rows]
    for c in model.columns(target):
        if c["role"] == "expected":
            mask = ((1 << c["width"]) - 1) << c["lsb"]
            ints = [v & ~mask for v in ints]
    w = rows.shape[1]
    for k, v in enumerate(ints):
        out[k] = [(v >> (32 * i)) & 0xFFFFFFFF for i in range(w)]
    return out


def raises(f, *needles):
    try:
        f()
    except gbump.GbumpError as e:
        return all(n in str(e) for n in needles)
    return False


model = gbump.Config.load(config) if config else gbump.Config()

# The interface JSON, byte for byte, and the configuration it carries.
rtl = os.path.join(work, "rtl")
run("rtl", "--out", rtl)
ipath = os.path.join(rtl, model.top + ".json")
with open(ipath) as f:
    text = f.read()
iface = json.loads(text)
check(model.interface_json(iface["regenerate"]) == text, "interface_json equals gbump rtl's file")
check(gbump.Config.from_interface(ipath).hash == model.hash, "from_interface gives the same configuration")
check((model.latency, model.initiation_interval) == (iface["latency_cycles"], iface["initiation_interval"]), "latency and interval")
check(all(p["kind"] in ("control", "load", "fragment", "triangle", "result") for p in iface["ports"]), "every port has a kind")
fmts = model.formats
check(fmts["lh"]["width"] == model.as_dict()["lh_bits"], "the lh format is lh_bits wide")

# Random vectors at shininess 40, the stimulus stream and evaluation of the file's stimulus.
vec = os.path.join(work, "v")
run("vectors", "--source", "random:700", "--seed", "7", "--target", "top", "--target", "dot_clamp", "--format", "hex", "--shininess", "40", "--out", vec)
# Each column says when it enters, as the set's manifest does.
with open(os.path.join(vec, "random700_dot_clamp.json")) as f:
    man = json.load(f)
check([c["enters"] for c in model.columns("dot_clamp")] == [c["enters"] for c in man["columns"]], "columns' enters equal the manifest's")
w = model.record_words("top")
ref = rows_from_hex(os.path.join(vec, "random700_top.hex"), w)
(s,) = model.vectors("random:700", seed=7, shininess=40)
check(s["name"] == "random700" and s["shininess"] == 40 and np.array_equal(s["records"], ref), "vectors('random:700') equals the file")
stim = model.stimulus(7).next(700)
check(np.array_equal(stim, cleared(model, "top", ref)), "the stimulus stream is the file's stimulus")
model.shininess = 40
check(np.array_equal(model.eval("top", stim), ref), "eval of the stimulus equals the file")
check(np.array_equal(model.eval("top", stim[3]), ref[3]), "eval of one 1-D record")
fields = model.unpack("top", ref)
check(np.array_equal(model.pack("top", fields), ref), "pack(unpack(records)) is the identity")
stim_fields = {c["name"]: fields[c["name"]] for c in model.columns("top") if c["role"] == "stimulus"}
out = model.eval_fields("top", stim_fields)
check(all(np.array_equal(out[k], fields[k]) for k in fields), "eval_fields equals the file's fields")
pt = hex_words(os.path.join(vec, "random700_top_power_table.hex"))
check(model.power_table().tolist() == pt and model.rom("power_table", 40)["words"].tolist() == pt, "the power table equals the set's")

# A unit set from the same run, evaluated from its stimulus.
uw = model.record_words("dot_clamp")
uref = rows_from_hex(os.path.join(vec, "random700_dot_clamp.hex"), uw)
check(np.array_equal(model.eval("dot_clamp", cleared(model, "dot_clamp", uref)), uref), "dot_clamp eval equals the file")

# Corners (with their reasons) and an exhaustive unit sweep.
run("vectors", "--source", "corners", "--target", "top", "--format", "hex", "--out", vec)
(c,) = model.vectors("corners")
check(np.array_equal(c["records"], rows_from_hex(os.path.join(vec, "corners_top.hex"), w)), "corners equal the file")
with open(os.path.join(vec, "corners_catalogue.txt")) as f:
    check(c["reasons"] == [line.rstrip("\n").split("\t", 1)[1] for line in f], "corner reasons equal the catalogue")
run("vectors", "--source", "exhaustive:power_unit", "--format", "hex", "--out", vec)
(e,) = model.vectors("exhaustive:power_unit")
check(np.array_equal(e["records"], rows_from_hex(os.path.join(vec, "exhaustive_power_unit_power_unit.hex"), model.record_words("power_unit"))), "exhaustive:power_unit equals the file")

# A scene's fragments, in the scene's own configuration (as `--scene` picks it), 32x32.
if not config:
    subprocess.run([exe, "vectors", "--source", "scene:blend_split", "--size", "32x32", "--target", "top", "--format", "hex", "--out", vec], check=True, stdout=subprocess.DEVNULL)
    sc = gbump.Config.from_scene("blend_split")
    (g,) = sc.vectors("scene:blend_split", size=(32, 32))
    ref = rows_from_hex(os.path.join(vec, g["name"] + "_top.hex"), sc.record_words("top"))
    check(len(ref) > 0 and np.array_equal(g["records"], ref), "scene:blend_split equals the file")
    px = np.loadtxt(os.path.join(vec, g["name"] + "_top_pixels.txt"), dtype=np.uint32, ndmin=2)
    check(g["pixels"].shape == (len(ref), 2) and np.array_equal(g["pixels"], px), "scene:blend_split's pixels equal the file")
    with open(os.path.join(vec, g["name"] + "_top.json")) as f:
        check(json.load(f)["image_size"] == [32, 32] and list(g["image_size"]) == [32, 32], "the image size is the manifest's")
    check(len({(int(x), int(y)) for x, y in px}) == len(px) and px.max() < 32, "each record has its own pixel, inside the image")
    # Within a triangle (records after its first), pixel order: rows from the top, x increasing.
    at = px[:, 1].astype(np.int64) * 32 + px[:, 0]
    same = sc.unpack("top", g["records"])["tri_start"].ravel()[1:] == 0
    check(same.any() and bool(np.all(np.diff(at)[same] > 0)), "a triangle's fragments come in pixel order")

# Bad input: the library's message, with its fix.
check(raises(lambda: gbump.Config("lights = 9\n", "bad.toml"), "bad.toml", "lights", "fix:"), "an out-of-range field")
check(raises(lambda: model.eval("top", np.zeros((2, w + 1), dtype=np.uint32)), "fix:"), "a record of the wrong width")
check(raises(lambda: model.eval("nonesuch", stim), "nonesuch", "fix:"), "an unknown target")
k_col = "tri_k" if "tri_k" in stim_fields else "in_k"
bad = dict(stim_fields, **{k_col: stim_fields[k_col] + 10000})
check(raises(lambda: model.pack("top", bad), k_col, "fix:"), "a value outside its format")
check(raises(lambda: model.vectors("random:0"), "fix:"), "an empty random set")
check(raises(lambda: model.rom("nonesuch"), "fix:"), "an unknown ROM")


def type_error(f):
    try:
        f()
    except TypeError as e:
        return "bool" in str(e) and "fix:" in str(e)
    return False


# True is 1 to Python, but no count, seed or shininess of gbump is a flag.
shininess_before = model.shininess
check(type_error(lambda: setattr(model, "shininess", True)), "a bool shininess is refused")
check(model.shininess == shininess_before, "a refused shininess leaves the table as it was")
check(type_error(lambda: model.stimulus(seed=True)), "a bool seed is refused")
check(type_error(lambda: model.vectors("random:5", seed=False)), "a bool seed of vectors is refused")
check(type_error(lambda: model.rom("power_table", shininess=True)), "a bool ROM shininess is refused")
forged = os.path.join(work, "forged.json")
with open(forged, "w") as f:
    json.dump(dict(iface, config_hash="0" * 16), f)
check(raises(lambda: gbump.Config.from_interface(forged), "config_hash", "fix:"), "an interface of another gbump")
# An old field name is read with a DeprecationWarning, which the caller's filters govern.
import warnings
with warnings.catch_warnings(record=True) as said:
    warnings.simplefilter("always")
    gbump.Config("dot_bits = 8\n", "old.toml")
check(
    len(said) == 1 and issubclass(said[0].category, DeprecationWarning) and "dot_frac_bits" in str(said[0].message),
    "an old field name warns through Python's warnings",
)
# Records of another dtype (int64, float, a list, uint32 in the other byte order) are refused
# as any bad input is, with GbumpError naming what was given; never cast.
for bad, name in [
    (stim.astype(np.int64), "dtype int64"),
    (stim.astype(np.float64), "dtype float64"),
    (stim.astype(">u4"), "dtype >u4"),
    (stim.tolist(), "a list"),
]:
    check(raises(lambda: model.eval("top", bad), name, "numpy uint32"), f"{name} records are refused with GbumpError")
# A count past MAX_BATCH_RECORDS is refused before anything is evaluated, as in C.
n_words = model.record_words("power_unit")
big = np.zeros((2**24 + 1, n_words), np.uint32)
check(raises(lambda: model.eval("power_unit", big), "MAX_BATCH_RECORDS"), "a batch past 2^24 records is refused")
check(raises(lambda: model.unpack("power_unit", big), "MAX_BATCH_RECORDS"), "an unpack past 2^24 records is refused")
del big
# An unsigned value past int64 is refused, not wrapped to a negative code.
check(
    raises(lambda: model.eval_fields("dot_clamp", {"b": np.array([[2**64 - 1, 0, 0]], np.uint64), "v": [[0, 0, 16384]]}), "18446744073709551615", "`b`"),
    "a uint64 past int64 is refused by its value",
)
check(raises(lambda: model.stimulus(1).next(-1), f"0..={2**24}"), "a negative count names the batch limit")
check(raises(lambda: model.vectors("random:0"), "1..="), "random:0 names the range it takes")
# A source is named as the call spelt it, not as gbump vectors' flag.
for bad in ["random:0", "bogus", "exhaustive:a/b"]:
    check(raises(lambda: model.vectors(bad), f'source "{bad}"') and not raises(lambda: model.vectors(bad), "--source"), f"{bad} is named in Python's spelling")
# A choice the source ignores, or a shininess the hardware cannot hold, is refused as
# `gbump vectors` refuses it (a set made without it would pass for what was asked).
check(raises(lambda: model.vectors("corners", seed=3), "seed=", "fix:"), "a seed of a corner set is refused")
check(raises(lambda: model.vectors("random:5", size=(8, 8)), "size=", "fix:"), "a size of a random set is refused")
check(raises(lambda: model.vectors("scene:blend_split", shininess=40), "shininess=", "fix:"), "a scene's shininess is refused")
rom_top = gbump.Config(model.toml + "power_rom = true\n", "rom.toml")
other = rom_top.shininess + 1
check(raises(lambda: rom_top.vectors("random:5", shininess=other), "ROM holding", "fix:"), "a ROM top's set of another shininess is refused")
check(raises(lambda: rom_top.rom("power_table", shininess=other), "ROM holding", "fix:"), "a ROM top's table of another shininess is refused")
check(rom_top.vectors("random:5", shininess=rom_top.shininess)[0]["shininess"] == rom_top.shininess, "a ROM top's own shininess is served")
# Changing the model while another thread's call holds it is a GbumpError naming the cause.
import threading

busy = model.stimulus(seed=9).next(200000)
done = threading.Event()


def evals():
    for _ in range(30):
        model.eval("top", busy)
    done.set()


worker = threading.Thread(target=evals)
worker.start()
refused, other_errors = 0, []
while not done.is_set():
    try:
        model.shininess = model.shininess
    except gbump.GbumpError as e:
        refused += "another thread" in str(e) and "fix:" in str(e)
    except Exception as e:
        other_errors.append(repr(e))
worker.join()
check(refused > 0 and not other_errors, f"a table load during another thread's eval is a GbumpError ({refused} refused, others {other_errors[:1]})")
# A batch that would not fit in memory is refused before it is allocated: the process lives.
code = f"""
import resource, gbump, numpy as np
with open("/proc/self/status") as f:
    vm = next(int(l.split()[1]) for l in f if l.startswith("VmSize:")) * 1024
resource.setrlimit(resource.RLIMIT_AS, (vm + (1 << 30), resource.RLIM_INFINITY))
m = gbump.Config({model.toml!r}, "plan.toml")
recs = np.zeros((1 << 23, m.record_words("top")), np.uint32)
try:
    m.unpack("top", recs)
except gbump.GbumpError as e:
    print("refused:", e)
"""
planned = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
import re

allowed = re.search(r"more than the ([0-9.]+) GiB allowed", planned.stdout)
check(
    planned.returncode == 0 and allowed is not None and float(allowed.group(1)) < 1.0 and "fix:" in planned.stdout,
    f"a batch past the room `ulimit -v` leaves is refused: {planned.stdout}{planned.stderr[-400:]}",
)
# An EMBM scene set lights each object with its own maps: loaded with set_env_map, eval gives
# back every record of the set; refused loads name the fix and change nothing.
embm_toml = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "configs", "embm.toml")
embm = gbump.Config.load(embm_toml)
for g in embm.vectors("scene:cg_wall_floor", size=(24, 24)):
    blank = cleared(embm, "top", g["records"])
    embm.set_env_map("diffuse", g["env_diffuse"])
    embm.set_env_map("specular", g["env_specular"])
    check(np.array_equal(embm.eval("top", blank), g["records"]), f"{g['name']} evaluates with its own maps")
    check(raises(lambda: embm.set_env_map("diffuse", g["env_diffuse"][:-1]), "words, not the", "fix:"), "a short map is refused")
    check(raises(lambda: embm.set_env_map("specular", [1 << 40] * len(g["env_diffuse"])), "wider than a texel", "fix:"), "a wide texel is refused")
    check(np.array_equal(embm.eval("top", blank), g["records"]), "a refused load leaves the maps as they were")
check(raises(lambda: model.set_env_map("diffuse", [0]), "not EMBM", "fix:"), "maps on a configuration without them are refused")
# `rom` gives what `gbump rom` writes: EMBM's power-up maps, and no table where the top reads none.
embm_roms = os.path.join(work, "embm_rom")
subprocess.run([exe, "rom", "--config", embm_toml, "--out", embm_roms], check=True, stdout=subprocess.DEVNULL)
for which in ["diffuse", "specular"]:
    name = f"env_{which}_default_{embm.hash[:8]}.hex"
    check(embm.rom(f"env_{which}")["words"].tolist() == hex_words(os.path.join(embm_roms, name)), f"rom env_{which} is {name}")
check(raises(lambda: embm.rom("power_table"), "reads no power table", "fix:"), "EMBM's absent power table is refused")
check(raises(lambda: embm.rom("bump_palette", shininess=3), "shininess=3", "EMBM", "fix:"), "a shininess under EMBM is refused")
# A child of os.fork() evaluates a large batch after its parent ran one (the parent's pool
# threads are not in the child; the module makes the child a pool of its own).
many = model.stimulus(seed=5).next(5000)
want = model.eval("top", many)
child = os.fork()
if child == 0:
    import signal

    signal.alarm(60)
    os._exit(0 if (model.eval("top", many) == want).all() else 3)
_, status = os.waitpid(child, 0)
check(status == 0, f"a forked child evaluates a batch after its parent (wait status {status})")
print(f"module check: {passed} passed, 0 failed")

"""Read gbump's interface JSON (and the vector manifests it goes with).

    python3 gbump_interface.py top|sources|init_file INTERFACE.json
    python3 gbump_interface.py results results.xml

prints the top module, the absolute Verilog sources (from the filelist the JSON names, whose
names are relative to the list itself) or the absolute power-up init file, for the Makefile;
`results` exits non-zero unless cocotb's results file holds tests and no failure.
"""

import json
import os
import sys


def load(path):
    with open(path) as f:
        return json.load(f)


def rtl_dir(path):
    return os.path.dirname(os.path.abspath(path))


def sources(path):
    iface = load(path)
    d = rtl_dir(path)
    with open(os.path.join(d, iface["files"]["filelist"])) as f:
        names = [line.strip() for line in f]
    return [os.path.join(d, n) for n in names if n and not n.startswith("//")]


def init_file(path):
    return os.path.join(rtl_dir(path), load(path)["parameters"]["INIT_FILE"]["default"])


def hex_words(path):
    """The words of a $readmemh text file (// comments and blank lines skipped)."""
    words = []
    with open(path) as f:
        for line in f:
            line = line.split("//", 1)[0].strip()
            if line:
                words.append(int(line, 16))
    return words


if __name__ == "__main__":
    what, path = sys.argv[1], sys.argv[2]
    if what == "top":
        print(load(path)["top"])
    elif what == "sources":
        print(" ".join(sources(path)))
    elif what == "init_file":
        print(init_file(path))
    elif what == "results":
        import xml.etree.ElementTree as ET

        root = ET.parse(path).getroot()
        cases = root.findall(".//testcase")
        bad = [c.get("name") for c in cases if c.find("failure") is not None or c.find("error") is not None]
        print(f"cocotb: {len(cases)} test(s), {len(bad)} failed {bad}")
        sys.exit(1 if bad or not cases else 0)
    else:
        sys.exit(f"unknown query {what}: top, sources or init_file")

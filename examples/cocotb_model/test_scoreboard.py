"""cocotb scoreboard for gbump's generated top, with the gbump Python module as the model.

Everything comes from the interface JSON ($GBUMP_INTERFACE) and the module: the model is
`gbump.Config.from_interface` (refused when the RTL is of another gbump), and each port is
handled by the entry of KINDS for its `kind`:
  control   clk, rst, in_valid/in_ready, out_valid: the protocol, by their documented names;
  load      a memory's load port: the power table is loaded with the table of
            $GBUMP_SHININESS from the module (and the model set to it); other memories keep
            their power-up contents, which are the model's;
  fragment  one stimulus column of the module's top record each, driven per fragment;
  triangle  the setup port of a per-triangle top (tri_valid/tri_ready and the tri_* state):
            a setup beat, in_valid low, before every record whose `tri_start` is 1; the
            model is given the state the top took at the setup's edge;
  result    one expected column each, checked per fragment.
A port of any other kind fails at once, naming it: a new kind of port is a new entry in
KINDS, and nothing else changes. Every stimulus column of the model's
record must be claimed by some port, so the model never assumes an input nobody drives.

Stimulus: the module's seeded random stream ($GBUMP_SEED, $GBUMP_COUNT records), offered with
random bubbles ($GBUMP_BUBBLES: the chance of a 1-3 cycle gap after an accept). The model
evaluates the ports as sampled at the accepting edge. Every result port is compared, every
fragment's latency (rising edges from its accept to the edge at which its out_valid is sampled
high) must be the interface's, accepts must keep the initiation interval, and every result
port must be 0 while out_valid is low. Stops after
$GBUMP_MAX_ERRORS problems.

Timing: inputs change just after falling edges; after ReadOnly, the values read are the ones
the next rising edge samples.
"""

import os
import random
from collections import deque

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge

import gbump
from gbump_interface import load

MAX_REPORTS = 10


def record_words(value, n):
    """A record as an integer -> n uint32 words, LSB first (the module's record rows)."""
    return np.array([(value >> (32 * i)) & 0xFFFFFFFF for i in range(n)], dtype=np.uint32)


def record_int(row):
    """A record row (uint32 words, LSB first) -> one integer."""
    return int.from_bytes(np.ascontiguousarray(row, dtype="<u4").tobytes(), "little")


def field(rec, col):
    return (rec >> col["lsb"]) & ((1 << col["width"]) - 1)


class Bench:
    """What every port handler may read: the DUT, the interface and the model."""

    def __init__(self, dut, iface, model):
        self.dut = dut
        self.iface = iface
        self.model = model
        self.columns = {c["name"]: c for c in model.columns("top")}
        self.claimed = set()

    def claim(self, port, role):
        """The model's column for `port`, checked: same name, role and width."""
        col = self.columns.get(port["name"])
        assert col is not None, f"port {port['name']} ({port['kind']}) has no column in the model's top record"
        assert col["role"] == role, f"port {port['name']}: the model's column is {col['role']}, not {role}"
        assert col["width"] == port["width"], f"port {port['name']}: {port['width']} bits, the model's column {col['width']}"
        self.claimed.add(col["name"])
        return col


class Control:
    """The handshake and clock ports, driven by the test body by their documented names."""

    NAMES = ("clk", "rst", "in_valid", "in_ready", "out_valid")
    # The setup handshake, on per-triangle tops (driven by the triangle handler), and
    # back-pressure, held high so every result is taken at its latency.
    SETUP = ("tri_valid", "tri_ready", "out_ready")

    def __init__(self, tb, ports):
        names = {p["name"] for p in ports}
        missing = [n for n in self.NAMES if n not in names]
        unknown = sorted(names - set(self.NAMES) - set(self.SETUP))
        self.out_ready = "out_ready" in names
        assert not missing, f"control ports {missing} are missing"
        assert not unknown, f"control ports {unknown}: this testbench does not know their protocol"

    def idle(self, dut):
        dut.rst.value = 1
        dut.in_valid.value = 0
        if self.out_ready:
            dut.out_ready.value = 1

    async def setup(self, tb):
        pass


class Load:
    """Memory load ports: the power table gets $GBUMP_SHININESS's table from the module."""

    def __init__(self, tb, ports):
        names = {p["name"] for p in ports}
        self.memories = tb.iface["memories"]
        for prefix in self.memories:
            for s in ("we", "waddr", "wdata"):
                assert f"{prefix}_{s}" in names, f"memory {prefix}: load port {prefix}_{s} missing"
        known = {f"{m}_{s}" for m in self.memories for s in ("we", "waddr", "wdata")}
        assert names <= known, f"load ports {sorted(names - known)} belong to no memory of the interface"
        # The power table is the memory whose init file the interface names as the power table's;
        # a top that reads none (EMBM, a squaring unit) keeps its port, unused, and gets no load.
        (self.pt,) = [m for m, d in self.memories.items() if d["init_file"] == tb.iface["power_table"]["init_file"]]
        self.load_table = self.memories[self.pt]["read"]

    def idle(self, dut):
        for m in self.memories:
            getattr(dut, f"{m}_we").value = 0

    async def setup(self, tb):
        if not self.load_table:
            return
        tb.model.shininess = int(os.environ.get("GBUMP_SHININESS", "40"))
        table = tb.model.power_table()
        mem = self.memories[self.pt]
        assert len(table) == mem["words"], f"{len(table)} power-table words, the interface states {mem['words']}"
        dut = tb.dut
        for addr, word in enumerate(table):
            getattr(dut, f"{self.pt}_we").value = 1
            getattr(dut, f"{self.pt}_waddr").value = addr
            getattr(dut, f"{self.pt}_wdata").value = int(word)
            await FallingEdge(dut.clk)
        getattr(dut, f"{self.pt}_we").value = 0


class Fragment:
    """Per-fragment inputs: each port is the model record's stimulus column of its name."""

    def __init__(self, tb, ports):
        self.cols = [(p["name"], tb.claim(p, "stimulus")) for p in ports]

    def idle(self, dut):
        for name, _ in self.cols:
            getattr(dut, name).value = 0

    async def setup(self, tb):
        pass

    def offer(self, dut, rec):
        for name, col in self.cols:
            getattr(dut, name).value = field(rec, col)

    def sample(self, dut):
        """The record these ports hold now (what the next rising edge samples)."""
        return sum(getattr(dut, name).value.integer << col["lsb"] for name, col in self.cols)


class Triangle:
    """The setup port: its state ports are the model record's stimulus columns of their names,
    and the record's `tri_start` column says which records begin a triangle."""

    def __init__(self, tb, ports):
        self.cols = [(p["name"], tb.claim(p, "stimulus")) for p in ports]
        self.start = tb.claim({"name": "tri_start", "kind": "triangle", "width": 1}, "stimulus")
        self.loaded = 0

    def idle(self, dut):
        dut.tri_valid.value = 0
        for name, _ in self.cols:
            getattr(dut, name).value = 0

    async def setup(self, tb):
        pass

    def starts(self, rec):
        return field(rec, self.start) == 1

    def offer(self, dut, rec):
        for name, col in self.cols:
            getattr(dut, name).value = field(rec, col)

    def capture(self, dut):
        """What the top takes at this setup's edge: the state its fragments will be shaded with."""
        self.loaded = sum(getattr(dut, name).value.integer << col["lsb"] for name, col in self.cols)


class Result:
    """Outputs: each port is the model record's expected column of its name."""

    def __init__(self, tb, ports):
        self.cols = [(p["name"], tb.claim(p, "expected")) for p in ports]

    def idle(self, dut):
        pass

    async def setup(self, tb):
        pass

    def check(self, dut, expected):
        """The outputs that differ from the model's record `expected`, described."""
        bad = []
        for name, col in self.cols:
            got = getattr(dut, name).value.integer
            want = field(expected, col)
            if got != want:
                bad.append(f"{name} expected {want:x} got {got:x}")
        return bad

    def gated(self, dut):
        """The outputs that are not 0 while out_valid is low (the integration notes promise 0)."""
        bad = []
        for name, _ in self.cols:
            v = getattr(dut, name).value
            if not v.is_resolvable or v.integer != 0:
                bad.append(f"{name} is not 0 while out_valid is low: {v}")
        return bad


KINDS = {"control": Control, "load": Load, "fragment": Fragment, "triangle": Triangle, "result": Result}


@cocotb.test()
async def model_scoreboard_with_bubbles(dut):
    path = os.environ["GBUMP_INTERFACE"]
    iface = load(path)
    model = gbump.Config.from_interface(path)
    assert model.top == iface["top"], f"model top {model.top}, interface {iface['top']}"
    lat = iface["latency_cycles"]
    ii = iface["initiation_interval"]
    assert (model.latency, model.initiation_interval) == (lat, ii), "the model's latency or interval differs from the interface's"
    tb = Bench(dut, iface, model)
    by_kind = {}
    for p in iface["ports"]:
        by_kind.setdefault(p["kind"], []).append(p)
    unknown = sorted(set(by_kind) - set(KINDS))
    assert not unknown, f"port kind(s) {unknown} ({[p['name'] for k in unknown for p in by_kind[k]]}): add a handler to KINDS"
    handlers = {k: KINDS[k](tb, ps) for k, ps in by_kind.items()}
    unclaimed = [c for c, d in tb.columns.items() if d["role"] == "stimulus" and c not in tb.claimed]
    assert not unclaimed, f"the model's stimulus columns {unclaimed} are driven by no port"
    frag, result, tri = handlers["fragment"], handlers["result"], handlers.get("triangle")
    words = model.record_words("top")

    count = int(os.environ.get("GBUMP_COUNT", "500"))
    stimulus = [record_int(r) for r in model.stimulus(int(os.environ.get("GBUMP_SEED", "1"))).next(count)]
    bubbles = float(os.environ.get("GBUMP_BUBBLES", "0.2"))
    rng = random.Random(int(os.environ.get("GBUMP_SEED", "1")))
    max_errors = int(os.environ.get("GBUMP_MAX_ERRORS", "20"))

    cocotb.start_soon(Clock(dut.clk, 10, units="ns").start())
    for h in handlers.values():
        h.idle(dut)
    # The clock's first rising edge comes with its start, racing rst: one more edge than the
    # model's reset_cycles makes that many certain.
    for _ in range(model.reset_cycles + 1):
        await FallingEdge(dut.clk)
    dut.rst.value = 0
    for h in handlers.values():
        await h.setup(tb)

    problems = []
    passed = 0
    in_flight = deque()  # (accepting edge, index, the model's record of the sampled ports)
    nxt = gap = edge = 0
    set_up = -1  # the record whose triangle setup the top took last
    last_accept = None
    limit = count * (ii + 4) * 2 + lat + 100
    while (nxt < count or in_flight) and edge < limit and len(problems) < max_errors:
        setup = False
        if nxt < count and gap == 0:
            setup = tri is not None and tri.starts(stimulus[nxt]) and set_up != nxt
            if setup:
                tri.offer(dut, stimulus[nxt])
            dut.in_valid.value = 0 if setup else 1
            frag.offer(dut, stimulus[nxt])
        else:
            dut.in_valid.value = 0
            gap = max(0, gap - 1)
        if tri is not None:
            dut.tri_valid.value = 1 if setup else 0
        await ReadOnly()
        valid = dut.in_valid.value == 1
        if valid and dut.in_ready.value == 1:
            if last_accept is not None and edge - last_accept < ii:
                problems.append(f"accepts {edge - last_accept} edges apart, the interface states {ii} (edge {edge})")
            # A fragment taken at a setup's edge belongs to the previous triangle.
            sampled = frag.sample(dut) | (tri.loaded if tri is not None else 0)
            expected = record_int(model.eval("top", record_words(sampled, words)))
            in_flight.append((edge, nxt, expected))
            last_accept = edge
            nxt += 1
            if rng.random() < bubbles:
                gap = rng.randint(1, 3)
        elif valid and (last_accept is None or edge - last_accept >= ii):
            problems.append(f"in_ready low beyond the initiation interval {ii} (edge {edge})")
        if setup and dut.tri_ready.value == 1:
            tri.capture(dut)
            set_up = nxt
        if dut.out_valid.value == 1:
            if not in_flight:
                problems.append(f"out_valid with no fragment in flight (edge {edge})")
            else:
                accepted, i, expected = in_flight.popleft()
                if edge - accepted != lat:
                    problems.append(f"fragment {i}: latency {edge - accepted}, the interface states {lat}")
                bad = result.check(dut, expected)
                if bad:
                    # The stimulus in the per-field form, for the report.
                    f = model.unpack("top", record_words(expected, words))
                    stim = ", ".join(f"{c}={f[c][0].tolist()}" for c, d in tb.columns.items() if d["role"] == "stimulus")
                    problems.append(f"fragment {i}: {'; '.join(bad)} ({stim})")
                else:
                    passed += 1
        else:
            problems.extend(f"{b} (edge {edge})" for b in result.gated(dut))
        await RisingEdge(dut.clk)
        await FallingEdge(dut.clk)
        edge += 1
    if len(problems) >= max_errors:
        dut._log.error("stopping after %d problems", len(problems))
    elif nxt < count or in_flight:
        problems.append(f"timed out after {edge} edges: {nxt} of {count} accepted, {len(in_flight)} in flight")
    dut._log.info("%d passed, %d failed", passed, len(problems))
    for p in problems[:MAX_REPORTS]:
        dut._log.error("MISMATCH %s", p)
    assert not problems, f"{len(problems)} problems, first: {problems[0]}"
    assert passed == count, f"{passed} of {count} fragments checked"

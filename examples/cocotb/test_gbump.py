"""cocotb test of gbump's generated top, written only from its interface JSON.

Port names and widths, the latency, the initiation interval and the power table's size come
from the interface JSON ($GBUMP_INTERFACE); the records, their column layout and the power
table from the vector manifest ($GBUMP_VECTORS). The test resets the pipeline, loads a power
table through the load port (power_table_we/power_table_waddr/power_table_wdata; $GBUMP_TABLE or the set's own), streams
every record with random bubbles ($GBUMP_BUBBLES: chance of a 1-3 cycle gap, seeded by
$GBUMP_SEED), and checks every out_c, the latency of every vector (rising edges from the
accepting edge to the edge at which its out_valid is first sampled high) and the spacing of
accepts (the initiation interval), and that out_c is 0 whenever out_valid is low. A per-triangle top (its interface has `bump_state.at` =
"triangle") gets a setup beat on tri_valid/tri_ready, in_valid low, before every record whose
`tri_start` column is 1. Stops after $GBUMP_MAX_ERRORS (default 20) mismatches.

Timing convention: inputs change at falling edges; after they settle, the values read are the
ones the next rising edge samples (the outputs are registered and change only after a rising
edge).
"""

import os
import random
from collections import deque

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge

from gbump_interface import hex_words, load

MAX_REPORTS = 10


def field(rec, col):
    return (rec >> col["lsb"]) & ((1 << col["width"]) - 1)


@cocotb.test()
async def vectors_match_with_bubbles_and_a_loaded_table(dut):
    iface = load(os.environ["GBUMP_INTERFACE"])
    man_path = os.environ["GBUMP_VECTORS"]
    man = load(man_path)
    man_dir = os.path.dirname(man_path)
    assert man["target"] == "top", f"{man_path} is a {man['target']} set; the example drives the top"
    assert man["config_hash"] == iface["config_hash"], "vectors and RTL are of different configurations"
    lat = iface["latency_cycles"]
    ii = iface["initiation_interval"]
    ports = {p["name"]: p for p in iface["ports"]}
    cols = man["columns"]
    stim = [c for c in cols if c["role"] == "stimulus"]
    (out,) = [c for c in cols if c["role"] == "expected"]
    per_triangle = iface["bump_state"]["at"] == "triangle"
    tri_start = next((c for c in cols if c["name"] == "tri_start"), None)
    assert per_triangle == (tri_start is not None), "vectors and RTL disagree on where the bump state lives"
    stim = [c for c in stim if c is not tri_start]
    for c in stim + [out]:
        assert c["name"] in ports, f"column {c['name']} is not a port of {iface['top']}"
        assert ports[c["name"]]["width"] == c["width"], f"column {c['name']}: width differs from the port's"
    records = hex_words(os.path.join(man_dir, man["hex"]["name"]))
    assert len(records) == man["count"] > 0, "the vector file does not hold the manifest's count"
    table_path = os.environ.get("GBUMP_TABLE") or os.path.join(man_dir, man["power_table"]["name"])
    table = hex_words(table_path)
    assert len(table) == iface["power_table"]["words"], f"{table_path}: {len(table)} words"
    bubbles = float(os.environ.get("GBUMP_BUBBLES", "0.2"))
    rng = random.Random(int(os.environ.get("GBUMP_SEED", "1")))

    cocotb.start_soon(Clock(dut.clk, 10, units="ns").start())
    dut.rst.value = 1
    dut.in_valid.value = 0
    if "out_ready" in ports:
        dut.out_ready.value = 1  # every result is taken when offered: exactly at its latency
    if per_triangle:
        dut.tri_valid.value = 0
    dut.power_table_we.value = 0
    dut.power_table_waddr.value = 0
    dut.power_table_wdata.value = 0
    for c in stim:
        getattr(dut, c["name"]).value = 0
    for _ in range(3):
        await FallingEdge(dut.clk)
    dut.rst.value = 0
    for addr, word in enumerate(table):
        dut.power_table_we.value = 1
        dut.power_table_waddr.value = addr
        dut.power_table_wdata.value = word
        await FallingEdge(dut.clk)
    dut.power_table_we.value = 0

    problems = []
    passed = 0
    in_flight = deque()  # (accepting edge, record index)
    nxt = 0
    set_up = -1  # the record whose triangle setup was taken last
    gap = 0
    last_accept = None
    edge = 0
    limit = len(records) * (ii + 4) + lat + 100
    max_errors = int(os.environ.get("GBUMP_MAX_ERRORS", "20"))
    while (nxt < len(records) or in_flight) and edge < limit and len(problems) < max_errors:
        # Drive for the next rising edge (we are just after a falling edge).
        setup = False
        if nxt < len(records) and gap == 0:
            setup = per_triangle and field(records[nxt], tri_start) == 1 and set_up != nxt
            dut.in_valid.value = 0 if setup else 1
            for c in stim:
                getattr(dut, c["name"]).value = field(records[nxt], c)
        else:
            dut.in_valid.value = 0
            gap = max(0, gap - 1)
        if per_triangle:
            dut.tri_valid.value = 1 if setup else 0
        await ReadOnly()
        valid = dut.in_valid.value == 1
        ready = dut.in_ready.value == 1
        if setup and dut.tri_ready.value == 1:
            set_up = nxt
        if valid and ready:
            if last_accept is not None and edge - last_accept < ii:
                problems.append(f"accepts {edge - last_accept} edges apart, the interface states {ii} (edge {edge})")
            in_flight.append((edge, nxt))
            last_accept = edge
            nxt += 1
            if rng.random() < bubbles:
                gap = rng.randint(1, 3)
        elif valid and (last_accept is None or edge - last_accept >= ii):
            problems.append(f"in_ready low beyond the initiation interval {ii} (edge {edge})")
        if dut.out_valid.value == 1:
            if not in_flight:
                problems.append(f"out_valid with no fragment in flight (edge {edge})")
            else:
                accepted, i = in_flight.popleft()
                if edge - accepted != lat:
                    problems.append(f"vector {i}: latency {edge - accepted}, the interface states {lat}")
                want = field(records[i], out)
                got = dut.out_c.value.integer
                if got == want:
                    passed += 1
                else:
                    fields = ", ".join(f"{c['name']}={field(records[i], c):x}" for c in stim)
                    problems.append(f"vector {i}: out_c expected {want:x} got {got:x} ({fields})")
        elif not dut.out_c.value.is_resolvable or dut.out_c.value.integer != 0:
            # The integration notes promise out_c = 0 whenever out_valid is low.
            problems.append(f"out_c is not 0 while out_valid is low: {dut.out_c.value} (edge {edge})")
        await RisingEdge(dut.clk)
        await FallingEdge(dut.clk)
        edge += 1
    if len(problems) >= max_errors:
        dut._log.error("stopping after %d mismatches", len(problems))
    elif nxt < len(records) or in_flight:
        problems.append(f"timed out after {edge} edges: {nxt} of {len(records)} accepted, {len(in_flight)} in flight")
    dut._log.info("%d passed, %d failed", passed, len(problems))
    for p in problems[:MAX_REPORTS]:
        dut._log.error("MISMATCH %s", p)
    assert not problems, f"{len(problems)} mismatches, first: {problems[0]}"
    assert passed == len(records), f"{passed} of {len(records)} vectors checked"

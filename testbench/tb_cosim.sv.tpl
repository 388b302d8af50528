// Lockstep co-simulation testbench template (gbump fills the double-braced fields from the
// RTL folder's interface JSON). No vector file: every fragment comes from the golden model's
// own random stream (libgbump through DPI-C, package gbump_dpi_pkg), the model evaluates
// exactly what the top accepted at the accepting edge, and each out_valid is checked against
// it, with the latency and the initiation interval the interface JSON states.
// Plusargs: [+config=FILE] the model's configuration TOML (default: the built-in default)
//           [+seed=HEX] (hexadecimal, so every 64-bit seed passes whole; default 1)
//           [+count=N] fragments (default 1000)
//           [+bubbles=N] idles in_valid for 1-3 cycles before every Nth fragment
//           [+max_errors=N] (default 20)
// A stream record that starts a triangle (per-triangle tops: its tri_start column) is preceded
// by a setup beat on tri_valid/tri_ready with in_valid low; the model is given the state the
// top took at that edge. Stream record k is record k of `gbump vectors --source random:N --seed S`, so a failing
// fragment replays from a vector file. Ends with "N passed, N failed".
`timescale 1ns / 1ps
`default_nettype none
module tb_cosim;
    import gbump_dpi_pkg::*;
    parameter INIT_FILE = {{INIT_FILE}};
    localparam int LAT = {{LATENCY}};
    localparam int II = {{II}};
    // The longest the testbench waits on the top: for tri_ready or in_ready before a beat,
    // and for the last results after the stream. A top that stops answering fails with a
    // FATAL line after it, rather than hanging the simulator.
    localparam int WAIT_EDGES = LAT * 4 + 100;
    localparam int POWER_TABLE_WORDS = {{POWER_TABLE_WORDS}};
    localparam int FLIGHT = 64;
    logic clk = 1'b0;
    logic rst = 1'b1;
    logic power_table_we = 1'b0;
    logic [{{POWER_TABLE_ADDR_BITS}}-1:0] power_table_waddr = '0;
    logic [{{POWER_TABLE_DATA_BITS}}-1:0] power_table_wdata = '0;
    logic in_valid = 1'b0;
    wire in_ready;
    wire out_valid;
{{TRI_DECLS}}
{{DECLS}}
    {{TOP}} #(.INIT_FILE(INIT_FILE)) dut (
        .clk(clk), .rst(rst), .power_table_we(power_table_we), .power_table_waddr(power_table_waddr), .power_table_wdata(power_table_wdata),
        .in_valid(in_valid), .in_ready(in_ready), .out_valid(out_valid),
{{CONNECT}}
    );
    always #5 clk = ~clk;

    chandle model, stream;
    string cfg_file;
    longint seed;
    int count, bubbles, max_errors, gap, i, cycles;
    int lsb, width, lanes, expected;
    longint pw;
    gbump_record_t stim, acc, tri_state;
    // Per fragment in flight: the record the top accepted (the model's expected columns
    // filled at the accepting edge) and the edge of its accept.
    gbump_record_t flight [0:FLIGHT-1];
    int acc_cyc [0:FLIGHT-1];
    int cyc = 0, last_acc = -1, n_in = 0, n_out = 0, passed = 0, failed = 0, timing_errors = 0;
{{LSB_DECLS}}

    // Exit code 1 on any failure, for a runner other than gbump; the last line is then the
    // mark gbump's verdict reads past. ($fatal would abort with SIGABRT under Verilator.)
    task automatic end_run(input bit bad);
        if (bad) begin
            $display("{{EXIT_MARK}}");
            $c("Verilated::runFlushCallbacks(); Verilated::runExitCallbacks(); std::exit(1);");
        end
        $finish;
    endtask

    task automatic finish_run;
        $display("%0d passed, %0d failed", passed, failed);
        if (passed + failed == 0) $display("FATAL: no fragments were checked");
        end_run(failed > 0 || passed + failed == 0);
    endtask

    task automatic fatal(input string msg);
        $display("FATAL: %0s", msg);
        end_run(1);
    endtask

    // The model's column `name` of the top record must have the port's width.
    task automatic column(input string name, input int port_width, output int at);
        if (gbump_column(model, "top", name, lsb, width, lanes, expected) != 0) fatal(gbump_last_error());
        if (width != port_width)
            fatal($sformatf("column %0s: the model's record has %0d bits, the RTL's port %0d: the RTL is of another configuration (interface JSON hash {{HASH}}, model %0s)", name, width, port_width, gbump_config_hash(model)));
        at = lsb;
    endtask

    // Until the top takes the beat on offer, at most WAIT_EDGES edges.
    task automatic wait_for_tri_ready;
        int waited;
        waited = 0;
        while (!tri_ready) begin
            if (waited == WAIT_EDGES) fatal($sformatf("tri_ready stayed low for %0d edges before record %0d: the top stopped taking setups", waited, n_in));
            @(negedge clk);
            waited = waited + 1;
        end
    endtask

    task automatic wait_for_in_ready;
        int waited;
        waited = 0;
        while (!in_ready) begin
            if (waited == WAIT_EDGES) fatal($sformatf("in_ready stayed low for %0d edges before record %0d: the top stopped taking fragments", waited, n_in));
            @(negedge clk);
            waited = waited + 1;
        end
    endtask

    task automatic mismatch_stop;
        if (failed >= max_errors) begin
            $display("stopping after %0d mismatches", failed);
            finish_run();
        end
    endtask

    initial begin
        if (!$value$plusargs("seed=%h", seed)) seed = 1;
        if (!$value$plusargs("count=%d", count)) count = 1000;
        if (!$value$plusargs("bubbles=%d", bubbles)) bubbles = 0;
        if (!$value$plusargs("max_errors=%d", max_errors)) max_errors = 20;
        if (gbump_abi_version() != GBUMP_ABI_VERSION)
            fatal($sformatf("libgbump ABI %0d, package %0d: rebuild the testbench against this library", gbump_abi_version(), GBUMP_ABI_VERSION));
        if ($value$plusargs("config=%s", cfg_file)) model = gbump_config_from_file(cfg_file);
        else model = gbump_config_default();
        if (model == null) fatal(gbump_last_error());
        if (gbump_latency(model) != LAT) fatal($sformatf("the model's latency is %0d, the interface JSON's %0d: the RTL is of another configuration", gbump_latency(model), LAT));
        if (gbump_initiation_interval(model) != II) fatal($sformatf("the model's initiation interval is %0d, the interface JSON's %0d", gbump_initiation_interval(model), II));
        if (gbump_power_words(model) != POWER_TABLE_WORDS) fatal($sformatf("the model's power table has %0d words, the RTL's %0d", gbump_power_words(model), POWER_TABLE_WORDS));
{{COLUMNS}}
        $display("cosim: model %0s (config %0s), seed %0d, %0d fragments", gbump_module_name(model), gbump_config_hash(model), $unsigned(seed), count);
        stream = gbump_stim_new(model, seed);
        if (stream == null) fatal(gbump_last_error());
        // Reset for exactly the documented edges.
        repeat (gbump_reset_cycles(model)) @(negedge clk);
        rst = 1'b0;
        // The model's table through the load port, word by word.
        for (i = 0; i < POWER_TABLE_WORDS; i = i + 1) begin
            power_table_we = 1'b1;
            power_table_waddr = i[{{POWER_TABLE_ADDR_BITS}}-1:0];
            pw = gbump_power_word(model, i);
            power_table_wdata = pw[{{POWER_TABLE_DATA_BITS}}-1:0];
            @(negedge clk);
        end
        power_table_we = 1'b0;
        while (n_in < count) begin
            if (bubbles > 0 && n_in % bubbles == bubbles - 1) begin
                in_valid = 1'b0;
                for (gap = 0; gap <= (n_in / bubbles) % 3; gap = gap + 1) @(negedge clk);
            end
            if (gbump_stim_next(stream, stim) != 0) fatal(gbump_last_error());
{{ASSIGN}}
            if ({{TRI_START}}) begin
                in_valid = 1'b0;
                tri_valid = 1'b1;
                wait_for_tri_ready();
                @(negedge clk);
                tri_valid = 1'b0;
            end
            in_valid = 1'b1;
            wait_for_in_ready();
            @(negedge clk);
        end
        in_valid = 1'b0;
        cycles = 0;
        while (n_out < n_in && cycles < WAIT_EDGES) begin @(negedge clk); cycles = cycles + 1; end
        if (n_out != n_in) begin
            $display("MISMATCH: %0d fragments went in but %0d came out", n_in, n_out);
            failed = failed + (n_in - n_out);
        end
        gbump_stim_free(stream);
        gbump_config_free(model);
        finish_run();
    end

    task automatic timing_error(input int got, input int want, input string what);
        failed = failed + 1;
        timing_errors = timing_errors + 1;
        if (timing_errors <= max_errors)
            $display("MISMATCH timing: %0s: %0d rising edges, the interface states %0d (fragment %0d, edge %0d)", what, got, want, n_out, cyc);
        mismatch_stop();
    endtask

    // No output may be X or Z after reset, and every data output is 0 while out_valid is low.
    int gate_reports = 0;
    task automatic gate_report(input string what);
        failed = failed + 1;
        gate_reports = gate_reports + 1;
        if (gate_reports <= max_errors) $display("MISMATCH: %0s", what);
        mismatch_stop();
    endtask
    always @(negedge clk) begin
        if (!rst && ((^{out_valid, in_ready{{OUT_XCHECK}}}) === 1'bx)) begin
            failed = failed + 1;
            if (failed <= max_errors) $display("MISMATCH: X on outputs after reset at %0t", $time);
            mismatch_stop();
        end else if (!rst && out_valid === 1'b0) begin
{{OUT_GATE}}
        end
    end

    // Sampled at the rising edge, before the design's registers take their new values: the
    // model evaluates the ports as the top takes them.
    always @(posedge clk) begin
        if (!rst && in_valid && in_ready) begin
            if (last_acc >= 0 && cyc - last_acc < II) timing_error(cyc - last_acc, II, "accepts closer than the initiation interval");
            if (n_in - n_out >= FLIGHT) fatal($sformatf("more than %0d fragments in flight", FLIGHT));
            acc = '0;
{{PACK}}
            if (gbump_eval(model, "top", acc, flight[n_in % FLIGHT]) != 0) fatal(gbump_last_error());
            acc_cyc[n_in % FLIGHT] = cyc;
            last_acc = cyc;
            n_in = n_in + 1;
        end else if (!rst && in_valid && !in_ready && (last_acc < 0 || cyc - last_acc >= II)) begin
            timing_error(last_acc < 0 ? cyc : cyc - last_acc, II, "in_ready low beyond the initiation interval");
        end
        // After the fragment's packing: a fragment taken at the same edge belongs to the
        // previous triangle.
        if (!rst && tri_valid && tri_ready) begin
            tri_state = '0;
{{TRI_CAPTURE}}
        end
        if (!rst && out_valid) begin
            if (n_out >= n_in) timing_error(0, LAT, "out_valid with no fragment in flight");
            else begin
                if (cyc - acc_cyc[n_out % FLIGHT] != LAT) timing_error(cyc - acc_cyc[n_out % FLIGHT], LAT, "latency");
                acc = flight[n_out % FLIGHT];
                if ({{OUT_EQUAL}}) passed = passed + 1;
                else begin
                    failed = failed + 1;
                    if (failed <= max_errors) begin
                        $display("MISMATCH fragment %0d (stream record %0d, seed %0d):", n_out, n_out, $unsigned(seed));
{{PRINT}}
                    end
                    mismatch_stop();
                end
                n_out = n_out + 1;
            end
        end
        cyc = cyc + 1;
    end
endmodule
`default_nettype wire

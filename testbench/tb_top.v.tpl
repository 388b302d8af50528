// Top-level testbench template (gbump fills the double-braced fields per configuration).
// Streams $readmemh-style text vectors (one record per line) through the pipeline with
// valid/ready, checks every out_c in order against the record's expected colour, and checks
// the timing the interface file states for every vector: out_valid is sampled high exactly
// LAT rising edges after the edge that accepted the fragment, and accepts are exactly II
// edges apart whenever a fragment was on offer. A record that starts a triangle (per-triangle
// tops: its tri_start bit) is preceded by a setup beat on tri_valid/tri_ready carrying the
// record's tri_* columns, with in_valid low. Stops after +max_errors mismatches (default
// 20) and ends with "N passed, N failed".
// Plusargs: +vectors=FILE  [+table=FILE] loads the power table through the load port; without
//           it the pipeline runs on its power-up contents (INIT_FILE)
//           [+bubbles=N] idles in_valid for 1-3 cycles before every Nth record
//           [+MEMORY=FILE] loads another memory of the top through its port after the power
//           table (EMBM's env_diffuse and env_specular: a scene set's object maps); without
//           it the memory keeps its power-up contents
//           [+stall=N] (tops with out_ready) holds out_ready low for the first 1-3 edges (at most N) of every N edges:
//           a result is then taken later than its latency, and in_ready may be low while
//           OUT_DEPTH accepted results are untaken, never otherwise
//           [+valid_during_reset] [+reset_after_load] (reset behaviour, see below)
//           [+count=N] the file must hold exactly N records (its manifest's `count`): without it
//           a file cut at a line boundary runs as a shorter set
//           [+waves=FILE.fst] [+max_errors=N]
// Every line of the file must be exactly the record's hex digits (a final newline, and a
// carriage return before it, allowed): a cut, joined or padded line is refused by number.
`timescale 1ns / 1ps
`default_nettype none
module {{TB_MODULE}};
    // The power table's power-up contents (a relative path resolves against the simulator's
    // working folder); override with -P {{TB_MODULE}}.INIT_FILE / -G INIT_FILE.
    parameter INIT_FILE = {{INIT_FILE}};
    localparam RB = {{RECORD_BITS}};
    localparam LAT = {{LATENCY}};
    // The longest the testbench waits on the top: for tri_ready or in_ready before a beat,
    // and for the last results after the file. A top that stops answering fails with a
    // FATAL line after it, rather than hanging the simulator.
    localparam WAIT_EDGES = LAT * 4 + 100;
    localparam POWER_TABLE_WORDS = {{POWER_TABLE_WORDS}};
    // Hex digits of a record's line.
    localparam HD = {{HEX_DIGITS}};
    reg clk = 1'b0;
    reg rst = 1'b1;
    reg power_table_we = 1'b0;
    reg [{{POWER_TABLE_ADDR_BITS}}-1:0] power_table_waddr = 0;
    reg [{{POWER_TABLE_DATA_BITS}}-1:0] power_table_wdata = 0;
    reg in_valid = 1'b0;
    wire in_ready;
    wire out_valid;
{{DECLS}}
    {{TOP}} #({{DUT_PARAMS}}) dut (
        .clk(clk), .rst(rst), .power_table_we(power_table_we), .power_table_waddr(power_table_waddr), .power_table_wdata(power_table_wdata),
        .in_valid(in_valid), .in_ready(in_ready), .out_valid(out_valid),
{{CONNECT}}
    );
    always #5 clk = ~clk;

    reg [RB-1:0] stim;
    reg [RB-1:0] chk;
    reg [{{POWER_TABLE_DATA_BITS}}-1:0] table_mem [0:POWER_TABLE_WORDS-1];
    reg [8*512-1:0] vec_file;
    reg [8*512-1:0] table_file;
    reg [8*512-1:0] wave_file;
    integer fin, fchk, code, i, cycles, max_errors, bubbles, gap;
    // Timing: the edge count, the edge of every accept still in flight, the last accept.
    localparam II = {{II}};
    // Tops with out_ready: the output buffer's depth (0: no out_ready, results are taken when
    // offered). A result is offered (out_valid) from LAT edges after its accept on, never
    // before, and stays offered until taken.
    localparam OUT_DEPTH = {{OUT_DEPTH}};
    integer stall = 0;
    // Per-triangle tops: a setup loads bank (setups so far + 1) % TRI_BANKS, and may do so
    // from BANK_HOLD edges after the accept of that bank's last fragment on, not before; and
    // it spans SETUP_EDGES edges from the first it is offered at (its accept is SETUP_EDGES - 1
    // edges after that one at the earliest). From both on, tri_ready is high.
    localparam TRI_BANKS = {{TRI_BANKS}};
    localparam BANK_HOLD = {{BANK_HOLD}};
    localparam SETUP_EDGES = {{SETUP_EDGES}};
    integer frag_edge [0:TRI_BANKS-1];
    integer n_setup = 0;
    integer bank_at;
    integer offer_at;
    reg offered = 1'b0;
    localparam FLIGHT = 64;
    integer cyc = 0;
    integer acc_cyc [0:FLIGHT-1];
    integer last_acc = -1;
    integer timing_errors = 0;
    reg load_table;
    integer n_in = 0;
    // Edges the current beat has waited for its handshake (at most WAIT_EDGES).
    integer waited = 0;
    integer n_tri = 0;
    integer tri_waits = 0;
    integer n_out = 0;
    integer passed = 0;
    integer failed = 0;
    reg done = 1'b0;

    // The digest of the records checked, printed beside the summary so a pass shows which
    // records were compared: each record's 64-bit slices XORed, taken as d = rotl(d, 1) ^ f.
    localparam RBP = (RB + 63) / 64 * 64;
    reg [63:0] digest = 64'd0;
    reg [RBP-1:0] dpad;
    reg [63:0] dfold;
    integer dk;
    task fold(input [RB-1:0] r);
        begin
            dpad = r;
            dfold = 64'd0;
            for (dk = 0; dk < RBP; dk = dk + 64) dfold = dfold ^ dpad[dk +: 64];
            digest = {digest[62:0], digest[63]} ^ dfold;
        end
    endtask

    // Exit code 1 when anything failed or the run gave up, for scripts and FuseSoC: the
    // run's last line is then {{EXIT_MARK}}, which gbump's verdict reads past.
    reg gave_up = 1'b0;
    task end_run(input bad);
        begin
            // Under Verilator $fatal aborts (SIGABRT, a core file): the binary exits through C++,
            // after what $finish would run (a waveform closed, buffers flushed).
`ifdef VERILATOR
            if (bad) begin $display("{{EXIT_MARK}}"); $c("Verilated::runFlushCallbacks(); Verilated::runExitCallbacks(); std::exit(1);"); end
`else
            if (bad) $fatal(1, "{{EXIT_MARK}}");
`endif
            $finish;
        end
    endtask

    // The vector file's current line, read whole (two characters more than a record's, so
    // that a longer line shows), and what follows a record's digits on it.
    reg [8*(HD+2)-1:0] line;
    reg [8*(HD+2)-1:0] rest;
    integer len;
    integer line_no = 0;
    integer want_count;
    // The character being decoded.
    reg [7:0] chr;
    integer ch;
    integer got;
    reg [8*HD-1:0] digits;

    // The next record of the vector file into stim: code 1, or 0 at the end of the file; a
    // line that is not exactly a record's HD hex digits is refused by its number (code -1,
    // the run given up). A line is read whole, so a space, a joined or a cut line cannot be
    // read as records of another width.
    task read_stim;
        begin
            code = 0;
            got = 1;
            // Blank lines (a trailing one, say) are passed over, as $readmemh passes them.
            while (code == 0 && got > 0) begin
                line = 0;
                got = $fgets(line, fin);
                len = got;
                if (got > 0) line_no = line_no + 1;
                if (len > 0 && line[7:0] == 8'h0a) begin line = line >> 8; len = len - 1; end
                if (len > 0 && line[7:0] == 8'h0d) begin line = line >> 8; len = len - 1; end
                if (len > 0) read_line;
            end
        end
    endtask

    // The record on the current line (`len` characters, its line end removed) into stim: code
    // 1, or -1 with the line refused by number.
    task read_line;
        begin
            // Left-aligned, the first character in the top byte.
            line = line << (8 * (HD + 2 - len));
            code = 1;
            if (len != HD) begin
                $display("FATAL: %0s line %0d: %0d characters, where a record is %0d hex digits (a cut or joined line, or a set of another configuration)", vec_file, line_no, len, HD);
                code = -1;
            end
`ifdef VERILATOR
            // Decoded a character at a time: Verilator's string functions stop at 2048 bits,
            // fewer than a wide record's line, and it is two-state (%h would read x as 0).
            stim = 0;
            for (ch = 0; code == 1 && ch < HD; ch = ch + 1) begin
                chr = line[8*(HD+2-ch)-1 -: 8];
                if (chr >= "0" && chr <= "9") stim = {stim[RB-5:0], chr[3:0]};
                else if ((chr >= "a" && chr <= "f") || (chr >= "A" && chr <= "F")) stim = {stim[RB-5:0], chr[3:0] + 4'd9};
                else if (chr == "x" || chr == "X" || chr == "z" || chr == "Z" || chr == "?") code = 2;
                else code = 3;
            end
`else
            // %h reads x, z and ? as unknown digits, which show in the value, and passes over
            // `_` and whitespace: the line must then be the value's own digits (lower-cased by
            // OR 0x20, which leaves digits alone and turns any other character into a
            // non-digit). A loop over the characters cost Icarus a sixth of its rate.
            rest = 0;
            if (code == 1 && $sscanf(line, "%h%s", stim, rest) != 1) code = 3;
            else if (code == 1 && (^stim) === 1'bx) code = 2;
            else if (code == 1) begin
                $sformat(digits, "%h", stim);
                if ((line[8*(HD+2)-1 -: 8*HD] | {HD{8'h20}}) !== digits) code = 3;
            end
`endif
            if (code == 2) $display("FATAL: %0s line %0d holds an x, z or ? digit", vec_file, line_no);
            if (code == 3) $display("FATAL: %0s line %0d: a character that is not a hex digit", vec_file, line_no);
            if (code > 1) code = -1;
            if (code < 0) gave_up = 1'b1;
        end
    endtask

    task finish_run;
        begin
            if (n_tri > 0) $display("%0d triangle setups, %0d edges waited for tri_ready, %0d edges in all", n_tri, tri_waits, cyc);
            $display("digest %016h", digest);
            $display("%0d passed, %0d failed", passed, failed);
            if (passed + failed == 0) $display("FATAL: no vectors were checked");
            end_run(gave_up || failed > 0 || passed + failed == 0);
        end
    endtask

    initial begin
        for (i = 0; i < TRI_BANKS; i = i + 1) frag_edge[i] = -1000000;
        if (!$value$plusargs("max_errors=%d", max_errors)) max_errors = 20;
        if (!$value$plusargs("vectors=%s", vec_file)) begin $display("FATAL: +vectors=FILE is missing"); end_run(1); end
        load_table = $value$plusargs("table=%s", table_file);
        if (!$value$plusargs("bubbles=%d", bubbles)) bubbles = 0;
        if (!$value$plusargs("stall=%d", stall)) stall = 0;
        if ($value$plusargs("waves=%s", wave_file)) begin $dumpfile(wave_file); $dumpvars(0, {{TB_MODULE}}); end
        if (load_table) $readmemh(table_file, table_mem);
        fin = $fopen(vec_file, "r");
        fchk = $fopen(vec_file, "r");
        if (fin == 0 || fchk == 0) begin $display("FATAL: cannot open %0s", vec_file); end_run(1); end
        // +valid_during_reset offers a fragment (all ones) through every reset edge: the top
        // must not take it. +reset_after_load resets again after the table is loaded: the
        // table must keep what was written.
        if ($test$plusargs("valid_during_reset")) begin
            stim = {RB{1'b1}};
{{ASSIGN}}
            in_valid = 1'b1;
            tri_valid = 1'b1;
        end
        repeat ({{RESET_CYCLES}}) @(negedge clk);
        rst = 1'b0;
        in_valid = 1'b0;
        tri_valid = 1'b0;
        if (load_table) begin
            for (i = 0; i < POWER_TABLE_WORDS; i = i + 1) begin
                power_table_we = 1'b1; power_table_waddr = i; power_table_wdata = table_mem[i];
                @(negedge clk);
            end
        end
        power_table_we = 1'b0;
{{MEM_LOAD}}
        if ($test$plusargs("reset_after_load")) begin
            rst = 1'b1;
            in_valid = $test$plusargs("valid_during_reset");
            tri_valid = in_valid;
            repeat ({{RESET_CYCLES}}) @(negedge clk);
            rst = 1'b0;
            in_valid = 1'b0;
            tri_valid = 1'b0;
        end
        read_stim;
        while (code == 1) begin
            if (bubbles > 0 && n_in % bubbles == bubbles - 1) begin
                in_valid = 1'b0;
                for (gap = 0; gap <= (n_in / bubbles) % 3; gap = gap + 1) @(negedge clk);
            end
{{ASSIGN}}
            if ({{TRI_START}}) begin
                // The setup beat: the fragment waits until its triangle is loaded.
                in_valid = 1'b0;
                tri_valid = 1'b1;
                waited = 0;
                while (!tri_ready) begin
                    if (waited == WAIT_EDGES) stopped("tri_ready", "setups");
                    @(negedge clk);
                    tri_waits = tri_waits + 1;
                    waited = waited + 1;
                end
                @(negedge clk);
                tri_valid = 1'b0;
                n_tri = n_tri + 1;
            end
            in_valid = 1'b1;
            waited = 0;
            while (!in_ready) begin
                if (waited == WAIT_EDGES) stopped("in_ready", "fragments");
                @(negedge clk);
                waited = waited + 1;
            end
            @(negedge clk);
            n_in = n_in + 1;
            read_stim;
        end
        if (!gave_up && $value$plusargs("count=%d", want_count) && n_in != want_count) begin
            $display("FATAL: %0s holds %0d records, where +count=%0d (its manifest's count) wants %0d: a cut or grown file", vec_file, n_in, want_count, want_count);
            gave_up = 1'b1;
        end
        in_valid = 1'b0;
        cycles = 0;
        while (n_out < n_in && cycles < WAIT_EDGES) begin @(negedge clk); cycles = cycles + 1; end
        if (n_out != n_in) begin
            $display("MISMATCH: %0d fragments went in but %0d came out", n_in, n_out);
            failed = failed + (n_in - n_out);
        end
        finish_run;
    end

    always @(negedge clk) if (OUT_DEPTH > 0 && stall > 0) out_ready_r = (cyc % stall) > (cyc / stall) % 3;

    // After reset no output may be X or Z, valid or not, and out_c is 0 while out_valid is
    // low (the integration notes promise both).
    integer x_reports = 0, gate_reports = 0;
    always @(negedge clk) begin
        if (!rst && ((^{out_valid, in_ready, out_c}) === 1'bx)) begin
            failed = failed + 1;
            x_reports = x_reports + 1;
            if (x_reports <= max_errors) $display("MISMATCH unit gbump_pipeline: X on outputs after reset at %0t: out_valid=%b in_ready=%b out_c=%h", $time, out_valid, in_ready, out_c);
        end else if (!rst && out_valid === 1'b0 && out_c !== 0) begin
            failed = failed + 1;
            gate_reports = gate_reports + 1;
            if (gate_reports <= max_errors) $display("MISMATCH unit gbump_pipeline: out_c is not 0 while out_valid is low at %0t: out_c=%h", $time, out_c);
        end
    end

    // A handshake the top left low for WAIT_EDGES edges: the run ends failed.
    task stopped(input [8*16-1:0] ready, input [8*16-1:0] what);
        begin
            $display("FATAL: %0s stayed low for %0d edges before record %0d: the top stopped taking %0s", ready, WAIT_EDGES, n_in, what);
            gave_up = 1'b1;
            finish_run;
        end
    endtask

    task timing_error(input integer got, input integer want, input [8*64-1:0] what);
        begin
            failed = failed + 1;
            timing_errors = timing_errors + 1;
            if (timing_errors <= max_errors)
                $display("MISMATCH unit gbump_pipeline timing: %0s: %0d rising edges, the interface states %0d (vector %0d, edge %0d)", what, got, want, n_out, cyc);
            if (failed >= max_errors) begin
                $display("stopping after %0d mismatches", failed);
                finish_run;
            end
        end
    endtask

    // Sampled at the rising edge, before the design's registers take their new values.
    always @(posedge clk) begin
        if (!rst && in_valid && in_ready) begin
            if (last_acc >= 0 && cyc - last_acc < II) timing_error(cyc - last_acc, II, "accepts closer than the initiation interval");
            if (n_in - n_out >= FLIGHT) begin $display("FATAL: more than %0d fragments in flight", FLIGHT); gave_up = 1'b1; finish_run; end
            if (OUT_DEPTH > 0 && n_in - n_out >= OUT_DEPTH) timing_error(n_in - n_out, OUT_DEPTH, "accepted while the output buffer's untaken results fill it");
            acc_cyc[n_in % FLIGHT] = cyc;
            last_acc = cyc;
            // A fragment taken at a setup's edge belongs to the previous triangle.
            frag_edge[n_setup % TRI_BANKS] = cyc;
        end else if (!rst && in_valid && !in_ready && (last_acc < 0 || cyc - last_acc >= II) && (OUT_DEPTH == 0 || n_in - n_out < OUT_DEPTH)) begin
            timing_error(last_acc < 0 ? cyc : cyc - last_acc, II, "in_ready low beyond the initiation interval");
        end
        if (!rst && tri_valid) begin
            if (!offered) begin offered = 1'b1; offer_at = cyc; end
            bank_at = frag_edge[(n_setup + 1) % TRI_BANKS];
            if (tri_ready && cyc - bank_at < BANK_HOLD) timing_error(cyc - bank_at, BANK_HOLD, "setup accepted while its bank is still read");
            else if (tri_ready && cyc - offer_at < SETUP_EDGES - 1) timing_error(cyc - offer_at + 1, SETUP_EDGES, "setup accepted before it spans its edges");
            else if (!tri_ready && cyc - bank_at >= BANK_HOLD && cyc - offer_at >= SETUP_EDGES - 1) timing_error(cyc - bank_at, BANK_HOLD, "tri_ready low beyond the bank hold");
            if (tri_ready) begin n_setup = n_setup + 1; offered = 1'b0; end
        end
        if (!rst && !out_valid && n_out < n_in && cyc - acc_cyc[n_out % FLIGHT] >= LAT)
            timing_error(cyc - acc_cyc[n_out % FLIGHT], LAT, "latency: the result is not offered");
        if (!rst && out_valid && n_out >= n_in + (in_valid && in_ready ? 1 : 0)) timing_error(0, LAT, "out_valid with no fragment in flight");
        else if (!rst && out_valid && cyc - acc_cyc[n_out % FLIGHT] < LAT) timing_error(cyc - acc_cyc[n_out % FLIGHT], LAT, "latency: the result is offered early");
        else if (!rst && out_valid && out_ready) begin
            code = $fscanf(fchk, "%h\n", chk);
            fold(chk);
            n_out = n_out + 1;
            if (out_c === chk[{{OUT_HI}}:{{OUT_LO}}]) passed = passed + 1;
            else begin
                failed = failed + 1;
                if (failed <= max_errors) begin
                    $display("MISMATCH unit gbump_pipeline vector %0d:", n_out - 1);
{{PRINT}}
                    $display("  out_c expected %h got %h", chk[{{OUT_HI}}:{{OUT_LO}}], out_c);
                end
                if (failed >= max_errors) begin
                    $display("stopping after %0d mismatches", failed);
                    finish_run;
                end
            end
        end
        cyc = cyc + 1;
    end
endmodule
`default_nettype wire

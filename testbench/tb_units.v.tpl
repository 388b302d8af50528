// Unit testbench template: every unit of the configuration instantiated once; +unit=NAME
// selects which one the text vectors drive. Records stream one per clock, as a unit takes
// them (initiation interval 1): record r's inputs are applied on falling edge r (a column
// whose manifest `enters` is e on edge r + e), and its outputs are checked on falling edge
// r + lat (the unit's latency, which the generator fills in per unit), before that edge's
// inputs change.
// Plusargs: +unit=NAME +vectors=FILE +table=FILE [+waves=FILE.fst] [+max_errors=N]
`timescale 1ns / 1ps
`default_nettype none
module tb_units;
    localparam POWER_TABLE_WORDS = {{POWER_TABLE_WORDS}};
    reg clk = 1'b0;
    reg power_table_we = 1'b0;
    reg [{{POWER_TABLE_ADDR_BITS}}-1:0] power_table_waddr = 0;
    reg [{{POWER_TABLE_DATA_BITS}}-1:0] power_table_wdata = 0;
    always #5 clk = ~clk;
{{DECLS}}
    reg [{{MAX_RB}}-1:0] rec;
    // hist[k]: the record applied k falling edges ago (hist[0]: this edge's); hv[k]: whether
    // it is one.
    localparam MAX_LAT = {{MAX_LAT}};
    reg [{{MAX_RB}}-1:0] hist [0:MAX_LAT];
    reg [{{MAX_RB}}-1:0] chk;
    reg [MAX_LAT:0] hv = 0;
    reg more;
    reg [{{POWER_TABLE_DATA_BITS}}-1:0] table_mem [0:POWER_TABLE_WORDS-1];
    reg [8*512-1:0] vec_file;
    reg [8*512-1:0] table_file;
    reg [8*512-1:0] wave_file;
    reg [8*32-1:0] unit;
    integer fin, code, i, n, m, max_errors, lat;
    integer passed = 0;
    integer failed = 0;
    reg ok;

    // The digest of the records checked, printed beside the summary so a pass shows which
    // records were compared: each record's 64-bit slices XORed, taken as d = rotl(d, 1) ^ f.
    localparam RBP = ({{MAX_RB}} + 63) / 64 * 64;
    reg [63:0] digest = 64'd0;
    reg [RBP-1:0] dpad;
    reg [63:0] dfold;
    integer dk;
    task fold(input [{{MAX_RB}}-1:0] r);
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

    task finish_run;
        begin
            $display("digest %016h", digest);
            $display("%0d passed, %0d failed", passed, failed);
            if (passed + failed == 0) $display("FATAL: no vectors were checked");
            end_run(gave_up || failed > 0 || passed + failed == 0);
        end
    endtask

    initial begin
        if (!$value$plusargs("max_errors=%d", max_errors)) max_errors = 20;
        if (!$value$plusargs("unit=%s", unit)) begin $display("FATAL: +unit=NAME is missing"); end_run(1); end
        if (!$value$plusargs("vectors=%s", vec_file)) begin $display("FATAL: +vectors=FILE is missing"); end_run(1); end
        if (!$value$plusargs("table=%s", table_file)) begin $display("FATAL: +table=FILE is missing"); end_run(1); end
        if ($value$plusargs("waves=%s", wave_file)) begin $dumpfile(wave_file); $dumpvars(0, tb_units); end
        $readmemh(table_file, table_mem);
        fin = $fopen(vec_file, "r");
        if (fin == 0) begin $display("FATAL: cannot open %0s", vec_file); end_run(1); end
        @(negedge clk);
        for (i = 0; i < POWER_TABLE_WORDS; i = i + 1) begin
            power_table_we = 1'b1; power_table_waddr = i; power_table_wdata = table_mem[i];
            @(negedge clk);
        end
        power_table_we = 1'b0;
        lat = 1;
{{LAT}}
        n = 0;
        m = 0;
        code = $fscanf(fin, "%h\n", rec);
        // %h also reads x, z and ? digits (unknown bits): a record holding one is refused, not
        // driven. (It reads `_` as a separator; `gbump regress` refuses such a set first.)
        more = code == 1 && (^rec) !== 1'bx;
        while (more || hv != 0) begin
            // The record applied `lat` falling edges ago has passed the unit's registers.
            if (hv[lat - 1]) begin
                chk = hist[lat - 1];
                fold(chk);
                ok = 1'b1;
{{CHECK}}
                if (ok) passed = passed + 1;
                else begin
                    failed = failed + 1;
                    if (failed >= max_errors) begin
                        $display("stopping after %0d mismatches", failed);
                        finish_run;
                    end
                end
                m = m + 1;
            end
            for (i = MAX_LAT; i > 0; i = i - 1) hist[i] = hist[i - 1];
            hist[0] = rec;
            hv = {hv[MAX_LAT-1:0], more};
            if (more) begin
                n = n + 1;
                code = $fscanf(fin, "%h\n", rec);
                more = code == 1 && (^rec) !== 1'bx;
            end
{{DRIVE}}
            @(negedge clk);
        end
        // The loop stops at the end of the file or at a character that is not a hex digit (the
        // part of its line before it, if any, was read as a record: the line is n or n + 1).
        if (code == 1) begin $display("FATAL: %0s: record %0d (line %0d) holds an x, z or ? digit", vec_file, n, n + 1); gave_up = 1'b1; end
        else if (!$feof(fin)) begin $display("FATAL: reading %0s stopped at a character that is not a hex digit, on line %0d or %0d", vec_file, n, n + 1); gave_up = 1'b1; end
        finish_run;
    end
endmodule
`default_nettype wire

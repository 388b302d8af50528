// Reads a ROM init file with $readmemh and prints every word, one per line, so a test can
// compare what a simulator loads with the model's table. Parameters set with -P / -G.
`timescale 1ns / 1ps
`default_nettype none
module rom_readback;
    parameter WIDTH = 9;
    parameter DEPTH = 256;
    parameter FILE = "rom.hex";
    reg [WIDTH-1:0] mem [0:DEPTH-1];
    integer i;
    initial begin
        $readmemh(FILE, mem);
        for (i = 0; i < DEPTH; i = i + 1) $display("%h", mem[i]);
        $finish;
    end
endmodule
`default_nettype wire

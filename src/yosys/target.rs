//! The targets Yosys synthesises for and the cell libraries it maps to: each FPGA target's
//! synthesis command and the column of the report (LUT, flip-flop, carry, DSP, block RAM,
//! LUT RAM) each of its cell names falls into.

use serde::{Deserialize, Serialize};

/// What `gbump area` measures against.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Target {
    /// NAND2 gate equivalents (`abc -g cmos2; stat -tech cmos`).
    Cmos,
    /// Lattice iCE40 (`synth_ice40`), placed and routed with nextpnr-ice40.
    Ice40,
    /// Lattice ECP5 (`synth_ecp5`).
    Ecp5,
    /// Xilinx 7-series (`synth_xilinx`).
    Xilinx,
}

/// What a cell is, for the columns of the report.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    Lut,
    FlipFlop,
    Carry,
    Dsp,
    BlockRam,
    LutRam,
    Other,
}

impl Target {
    pub fn name(self) -> &'static str {
        match self {
            Target::Cmos => "cmos",
            Target::Ice40 => "ice40",
            Target::Ecp5 => "ecp5",
            Target::Xilinx => "xilinx",
        }
    }

    /// The Yosys synthesis command for module `top` (FPGA targets only).
    pub fn synth(self, top: &str) -> String {
        match self {
            Target::Cmos => unreachable!("cmos has its own script, scripts::cmos_area"),
            Target::Ice40 => format!("synth_ice40 -top {top}"),
            Target::Ecp5 => format!("synth_ecp5 -top {top}"),
            // synth_xilinx keeps the hierarchy unless told, and adds I/O buffers a unit
            // synthesised alone does not have.
            Target::Xilinx => format!("synth_xilinx -flatten -noiopad -top {top}"),
        }
    }

    /// The cell names of each column, as the report's header states them.
    pub fn cell_names(self) -> [&'static str; 5] {
        // LUTs, flip-flops, carry, DSP, block RAM
        match self {
            Target::Ice40 => ["SB_LUT4", "SB_DFF*", "SB_CARRY", "SB_MAC16", "SB_RAM40_4K"],
            Target::Ecp5 => ["LUT4", "TRELLIS_FF", "CCU2C", "MULT18X18D", "DP16KD"],
            Target::Xilinx => ["LUT1-6", "FD*", "CARRY4", "DSP48E1", "RAMB18/36"],
            Target::Cmos => ["", "$_DFF*", "", "", ""],
        }
    }

    /// The column of a cell type of this target's library.
    pub fn classify(self, cell: &str) -> Class {
        let is = |names: &[&str]| names.contains(&cell);
        match self {
            Target::Ice40 => match cell {
                "SB_LUT4" => Class::Lut,
                c if c.starts_with("SB_DFF") => Class::FlipFlop,
                "SB_CARRY" => Class::Carry,
                "SB_MAC16" => Class::Dsp,
                c if c.starts_with("SB_RAM40_4K") || c == "SB_SPRAM256KA" => Class::BlockRam,
                _ => Class::Other,
            },
            Target::Ecp5 => match cell {
                "LUT4" => Class::Lut,
                "TRELLIS_FF" => Class::FlipFlop,
                "CCU2C" => Class::Carry,
                _ if is(&["MULT18X18D", "ALU54B"]) => Class::Dsp,
                _ if is(&["DP16KD", "PDPW16KD"]) => Class::BlockRam,
                "TRELLIS_DPR16X4" => Class::LutRam,
                _ => Class::Other,
            },
            Target::Xilinx => match cell {
                c if c.len() == 4 && c.starts_with("LUT") => Class::Lut,
                _ if is(&["FDRE", "FDSE", "FDCE", "FDPE"]) => Class::FlipFlop,
                _ if is(&["CARRY4", "CARRY8"]) => Class::Carry,
                c if c.starts_with("DSP48") => Class::Dsp,
                c if c.starts_with("RAMB18") || c.starts_with("RAMB36") => Class::BlockRam,
                c if c.starts_with("RAM") || c.starts_with("SRL") => Class::LutRam,
                _ => Class::Other,
            },
            Target::Cmos => match cell {
                c if c.starts_with("$_DFF") => Class::FlipFlop,
                _ => Class::Other,
            },
        }
    }
}

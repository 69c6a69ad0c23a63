//! What a run writes: the log and screen, thermo lines, dumps (text, VTU, pictures) and charts.

pub mod atom_table;
pub mod colors;
pub mod dump;
pub mod dump_dcd;
pub mod dump_image;
pub mod dump_vtu;
pub mod format;
pub mod log;
pub mod plot;
pub mod progress;
pub mod render;
pub mod thermo;

//! The verification harness: tables comparing methods with each other and with the references.

pub mod adhesion_peers;
pub mod baselines;
pub mod benchmarks;
pub mod comparison;
pub mod convergence;
pub mod fenicsx;
pub mod history;
pub mod html;
pub mod operator;
pub mod parts;
pub mod peers;
pub mod plan;
pub mod progress;
pub mod pulloff_records;
pub mod report;
pub mod report_tables;
pub mod speed_accuracy;
pub mod stability;
pub mod stored;
pub mod svg;
pub mod sweeps;
pub mod table;

//! The verification harness: studies that compare the methods with each other and with the
//! references ([`studies`]), the stored results of other codes and of earlier runs compared
//! with ours ([`records`]), the report that shows them ([`report`]), and the report's work as
//! independent jobs ([`report_jobs`], [`plan`]).

pub mod cases;
pub mod dataset;
pub mod grade;
pub mod plan;
pub mod progress;
pub mod records;
pub mod report;
pub mod report_jobs;
pub mod settings;
pub mod studies;

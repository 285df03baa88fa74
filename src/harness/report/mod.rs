//! The report: its contents as data ([`contents`]), its document and files ([`document`]), its tables ([`tables`], drawn by
//! [`table`]), charts ([`svg`]), HTML page ([`html`]) and the history of earlier reports
//! ([`history`]).

pub mod contents;
pub mod document;
pub mod history;
pub mod html;
pub mod svg;
pub mod table;
pub mod tables;

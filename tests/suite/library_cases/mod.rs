//! The library's rules checked through its public API on the built-in punches: the scene's
//! rules and its keyword form, the plausibility checks of a solution, and the typed solvers.

mod keywords;
mod methods;
mod scene;
mod solution;

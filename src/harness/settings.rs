//! The program's choices that the library takes as explicit values: the linear-solver backend
//! of every FEM model the harness and the command line build (`verify --linear-solver`, else
//! the environment's `RINGCONTACT_LINEAR_SOLVER`, else the library's built-in one), and the
//! FEM's trace (`RINGCONTACT_TRACE`).

use std::sync::OnceLock;

use ringcontact::methods::MethodOptions;
use ringcontact::sparse::{Backend, ENVIRONMENT_VARIABLE};

static LINEAR_SOLVER: OnceLock<Backend> = OnceLock::new();

/// Choose the backend of this program's FEM models (the `verify` binary's `--linear-solver`),
/// before any is built; only the first choice counts. Returns whether it was taken.
pub fn choose_linear_solver(backend: Backend) -> bool {
    LINEAR_SOLVER.set(backend).is_ok() || LINEAR_SOLVER.get() == Some(&backend)
}

/// The backend this program's FEM models use: the one chosen, else the environment's
/// `RINGCONTACT_LINEAR_SOLVER` (an unknown name is refused by the binary, ignored here), else
/// [`Backend::BUILT_IN`].
pub fn linear_solver() -> Backend {
    *LINEAR_SOLVER.get_or_init(|| {
        std::env::var(ENVIRONMENT_VARIABLE)
            .ok()
            .and_then(|name| name.parse().ok())
            .unwrap_or_default()
    })
}

/// Whether this program's FEM models trace each model on standard error (`RINGCONTACT_TRACE`
/// set).
pub fn trace() -> bool {
    std::env::var_os("RINGCONTACT_TRACE").is_some()
}

/// Method options with nothing set but this program's [`linear_solver`] and [`trace`].
pub fn method_options() -> MethodOptions {
    MethodOptions {
        linear_solver: Some(linear_solver()),
        trace: trace(),
        ..MethodOptions::default()
    }
}

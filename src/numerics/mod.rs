//! Numerical building blocks shared by the solvers: the complete elliptic integral of the first
//! kind, tanh-sinh quadrature on panels, Chebyshev interpolation and a safeguarded scalar root
//! finder. Everything here is dimensionless.

pub mod chebyshev;
pub mod elliptic;
pub mod golden;
pub mod prefetch;
pub mod richardson;
pub mod roots;
pub mod tanh_sinh;
pub mod zeroed;

//! Numerical building blocks shared by the solvers: the complete elliptic integral of the first
//! kind, tanh-sinh quadrature on panels, Chebyshev interpolation, a safeguarded scalar root
//! finder and minimisation on an interval (golden section, Brent). Everything here is dimensionless.

pub mod brent;
pub mod chebyshev;
pub mod elliptic;
pub mod gauss_legendre;
pub mod golden;
pub mod log_product;
pub mod prefetch;
pub mod richardson;
pub mod roots;
pub mod tanh_sinh;
pub mod zeroed;

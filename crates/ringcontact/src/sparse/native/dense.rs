//! Dense matrices whose storage padding is zero, and the dense Cholesky factorisation on them:
//! of the split solver's Schur complement, and of the cohesive model's compliance and Newton
//! steps (`crate::cohesive::equilibrium`).
//!
//! `faer` stores a column of `n` values in `n` rounded up to a multiple of eight (one 64-byte
//! vector), and leaves the rounding's rows uninitialised. Its dense kernels compute whole
//! vectors, padding rows included, and discard those rows' results: they are right whatever the
//! padding holds, but not equally fast. Memory the allocator hands out again still holds what
//! was freed there, and an index array read as `f64` is a subnormal number (a nonzero `usize`
//! below 2⁵² has a zero exponent field), whose arithmetic takes the processor's slow microcode
//! path: the same dense factorisation then takes two to seven times as long, depending only on
//! where its matrix was allocated (docs/decisions.md, "Where the constants come from"). Zeroing
//! the padding makes every solve take the fast path without touching the floating-point
//! environment.
//!
//! [`zero_padded`] allocates a matrix whose padding rows are written with zeros,
//! [`zeroed_scratch`] a kernel's scratch memory written with zeros, and [`DenseCholesky`]
//! factorises in place in such a matrix, with such scratch.

use std::mem::MaybeUninit;

use faer::dyn_stack::{MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::{cholesky_in_place, cholesky_in_place_scratch, LltError};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, MatMut, Par};

/// Values per `faer` column vector: a column's storage is its rows rounded up to a multiple of
/// this.
const VECTOR_VALUES: usize = 8;

/// An `nrows × ncols` zero matrix whose storage padding is zero as well: allocated with `nrows`
/// rounded up to a multiple of [`VECTOR_VALUES`] (every row written) and truncated to `nrows`
/// (which keeps the storage and its values).
pub(crate) fn zero_padded(nrows: usize, ncols: usize) -> Mat<f64> {
    let mut matrix = Mat::<f64>::zeros(nrows.next_multiple_of(VECTOR_VALUES), ncols);
    matrix.truncate(nrows, ncols);
    matrix
}

/// Scratch memory for a `faer` kernel that asks for `request`, every byte written with zero
/// (`MemStack::new` of it): `faer`'s temporary matrices in it are then zero-padded too.
pub(crate) fn zeroed_scratch(request: StackReq) -> Vec<MaybeUninit<u8>> {
    vec![MaybeUninit::new(0u8); request.unaligned_bytes_required()]
}

/// The Cholesky factor `L` of a dense symmetric positive definite matrix, `A = L Lᵀ`, kept in
/// zero-padded storage ([`zero_padded`]), its strict upper triangle zero.
#[derive(Clone, Debug)]
pub(crate) struct DenseCholesky {
    lower: Mat<f64>,
}

/// A dense factorisation that met a pivot `≤ 0`: the matrix is not positive definite.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct NotPositiveDefinite {
    /// The column whose pivot was not positive.
    pub column: usize,
}

impl DenseCholesky {
    /// Factorise the `n × n` matrix whose lower triangle `lower(i, j)` gives (`i ≥ j`), in
    /// zero-padded storage with zeroed scratch (`faer`'s blocked left-looking `L Lᵀ`).
    pub(crate) fn of_lower(
        n: usize,
        lower: impl Fn(usize, usize) -> f64,
    ) -> Result<Self, NotPositiveDefinite> {
        let mut factor = zero_padded(n, n);
        for j in 0..n {
            for i in j..n {
                factor[(i, j)] = lower(i, j);
            }
        }
        let request = cholesky_in_place_scratch::<f64>(n, Par::Seq, Default::default());
        let mut scratch = zeroed_scratch(request);
        cholesky_in_place(
            factor.as_mut(),
            Default::default(),
            Par::Seq,
            MemStack::new(&mut scratch),
            Default::default(),
        )
        .map_err(|LltError::NonPositivePivot { index }| NotPositiveDefinite { column: index })?;
        // The in-place factorisation leaves values in the strict upper triangle (`faer`'s own
        // `Llt` clears it afterwards too).
        for j in 1..n {
            for i in 0..j {
                factor[(i, j)] = 0.0;
            }
        }
        Ok(Self { lower: factor })
    }

    /// Overwrite `rhs` (one or more columns) with `A⁻¹ rhs = L⁻ᵀ L⁻¹ rhs`.
    pub(crate) fn solve_in_place(&self, mut rhs: MatMut<'_, f64>) {
        solve_lower_triangular_in_place(self.lower.as_ref(), rhs.as_mut(), Par::Seq);
        solve_upper_triangular_in_place(self.lower.transpose(), rhs, Par::Seq);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_padding_rows_of_a_zero_padded_matrix_are_zero() {
        for n in [1, 7, 8, 9, 158, 159] {
            let matrix = zero_padded(n, 3);
            let stride = matrix.col_stride() as usize;
            assert!(
                stride >= n && stride.is_multiple_of(VECTOR_VALUES),
                "n {n}: stride {stride}"
            );
            // SAFETY: the storage holds `stride` values per column, all written by `zeros`.
            let storage = unsafe { std::slice::from_raw_parts(matrix.as_ptr(), stride * 3) };
            assert!(storage.iter().all(|&v| v == 0.0), "n {n}");
        }
    }

    /// Against the closed form of a matrix whose factor is known: `A = L Lᵀ` for a chosen `L`.
    #[test]
    fn the_factor_and_the_solve_match_a_known_factorisation() {
        let n = 37;
        let known = Mat::<f64>::from_fn(n, n, |i, j| {
            if i == j {
                2.0 + i as f64 / 10.0
            } else if i > j {
                ((i * 3 + j * 5) % 7) as f64 / 7.0 - 0.4
            } else {
                0.0
            }
        });
        let a = &known * known.transpose();
        let cholesky = DenseCholesky::of_lower(n, |i, j| a[(i, j)]).expect("positive definite");
        for j in 0..n {
            for i in 0..n {
                let expected = known[(i, j)];
                assert!(
                    (cholesky.lower[(i, j)] - expected).abs() <= 1e-13,
                    "L[{i},{j}]"
                );
            }
        }
        let x = Mat::<f64>::from_fn(n, 2, |i, j| (i as f64 - 10.0) * (j as f64 + 1.0) / 7.0);
        let mut b = &a * &x;
        cholesky.solve_in_place(b.as_mut());
        for j in 0..2 {
            for i in 0..n {
                assert!((b[(i, j)] - x[(i, j)]).abs() <= 1e-12, "x[{i},{j}]");
            }
        }
    }

    #[test]
    fn a_matrix_that_is_not_positive_definite_is_refused_at_its_pivot() {
        // [[1, 2], [2, 1]]: the second pivot is 1 − 4 < 0.
        let a = [[1.0, 2.0], [2.0, 1.0]];
        assert_eq!(
            DenseCholesky::of_lower(2, |i, j| a[i][j]).unwrap_err(),
            NotPositiveDefinite { column: 1 }
        );
    }
}

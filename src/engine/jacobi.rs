//! LAMMPS' `MathEigen::jacobi3`: eigenvalues and eigenvectors of a symmetric 3x3 matrix by
//! Jacobi rotations, each pivot the largest off-diagonal entry (Jewett's jacobi_pd), in the
//! same order of operations, so that rigid-body axes (fix rigid/small) get LAMMPS' bits.

/// The order of the eigenvalues (LAMMPS' jacobi3 `sort` argument: -1 decreasing, 1 increasing).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Sort {
    Decreasing,
    Increasing,
}

/// Eigenvalues and eigenvectors (as columns), sorted; None if 50 sweeps did not converge.
pub fn jacobi3(mat: &[[f64; 3]; 3], sort: Sort) -> Option<([f64; 3], [[f64; 3]; 3])> {
    const N: usize = 3;
    // upper triangle is the working copy; below the diagonal holds backups during a rotation
    let mut m = *mat;
    let mut evec = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut max_idx = [0usize; N];
    for i in 0..N - 1 {
        max_idx[i] = max_entry_row(&m, i);
    }
    let max_iters = 50 * N * (N - 1) / 2;
    let mut n_iters = 0;
    while n_iters < max_iters {
        // largest off-diagonal entry
        let (mut i, mut j) = (0, max_idx[0]);
        let mut max_entry = m[i][j].abs();
        for r in 1..N - 1 {
            let c = max_idx[r];
            if m[r][c].abs() > max_entry {
                max_entry = m[r][c].abs();
                (i, j) = (r, c);
            }
        }
        // negligible next to the diagonal: zero it
        if m[i][i] + m[i][j] == m[i][i] && m[j][j] + m[i][j] == m[j][j] {
            m[i][j] = 0.0;
            max_idx[i] = max_entry_row(&m, i);
        }
        if m[i][j] == 0.0 {
            break;
        }
        let (c, s, t) = calc_rot(&m, i, j);
        apply_rot(&mut m, &mut max_idx, i, j, c, s, t);
        // rotate the eigenvector rows
        for v in 0..N {
            let eiv = evec[i][v];
            evec[i][v] = c * evec[i][v] - s * evec[j][v];
            evec[j][v] = s * eiv + c * evec[j][v];
        }
        n_iters += 1;
    }
    let mut eval = [m[0][0], m[1][1], m[2][2]];
    // selection sort (jacobi_pd's SortRows), rows swapped with their eigenvalues
    for i in 0..N - 1 {
        let mut best = i;
        for j in i + 1..N {
            let first = match sort {
                Sort::Decreasing => eval[j] > eval[best],
                Sort::Increasing => eval[j] < eval[best],
            };
            if first {
                best = j;
            }
        }
        eval.swap(i, best);
        evec.swap(i, best);
    }
    // rows to columns
    let mut cols = [[0.0; 3]; 3];
    for (r, row) in evec.iter().enumerate() {
        for (c, v) in row.iter().enumerate() {
            cols[c][r] = *v;
        }
    }
    (n_iters < max_iters).then_some((eval, cols))
}

fn max_entry_row(m: &[[f64; 3]; 3], i: usize) -> usize {
    let mut j_max = i + 1;
    for j in i + 2..3 {
        if m[i][j].abs() > m[i][j_max].abs() {
            j_max = j;
        }
    }
    j_max
}

/// cos, sin and tan of the rotation that zeroes m[i][j].
fn calc_rot(m: &[[f64; 3]; 3], i: usize, j: usize) -> (f64, f64, f64) {
    let mut t = 1.0;
    let m_jj_ii = m[j][j] - m[i][i];
    if m_jj_ii != 0.0 {
        let mut kappa = m_jj_ii;
        t = 0.0;
        let m_ij = m[i][j];
        if m_ij != 0.0 {
            kappa /= 2.0 * m_ij;
            t = 1.0 / ((1.0 + kappa * kappa).sqrt() + kappa.abs());
            if kappa < 0.0 {
                t = -t;
            }
        }
    }
    let c = 1.0 / (1.0 + t * t).sqrt();
    (c, c * t, t)
}

/// M' = R^T M R on the upper triangle, keeping the row maxima current (jacobi_pd's ApplyRot).
#[allow(clippy::too_many_arguments)]
fn apply_rot(m: &mut [[f64; 3]; 3], max_idx: &mut [usize; 3], i: usize, j: usize, c: f64, s: f64, t: f64) {
    const N: usize = 3;
    m[i][i] -= t * m[i][j];
    m[j][j] += t * m[i][j];
    m[i][j] = 0.0;
    for w in 0..i {
        m[i][w] = m[w][i];
        m[w][i] = c * m[w][i] - s * m[w][j];
        if i == max_idx[w] {
            max_idx[w] = max_entry_row(m, w);
        } else if m[w][i].abs() > m[w][max_idx[w]].abs() {
            max_idx[w] = i;
        }
    }
    for w in i + 1..j {
        m[w][i] = m[i][w];
        m[i][w] = c * m[i][w] - s * m[w][j];
    }
    for w in j + 1..N {
        m[w][i] = m[i][w];
        m[i][w] = c * m[i][w] - s * m[j][w];
    }
    max_idx[i] = max_entry_row(m, i);
    for w in 0..i {
        m[w][j] = s * m[i][w] + c * m[w][j];
        if j == max_idx[w] {
            max_idx[w] = max_entry_row(m, w);
        } else if m[w][j].abs() > m[w][max_idx[w]].abs() {
            max_idx[w] = j;
        }
    }
    for w in i + 1..j {
        m[w][j] = s * m[w][i] + c * m[w][j];
        if j == max_idx[w] {
            max_idx[w] = max_entry_row(m, w);
        } else if m[w][j].abs() > m[w][max_idx[w]].abs() {
            max_idx[w] = j;
        }
    }
    for w in j + 1..N {
        m[j][w] = s * m[w][i] + c * m[j][w];
    }
    max_idx[j] = max_entry_row(m, j);
}

#[cfg(test)]
mod tests {
    #[test]
    fn diagonalizes_a_symmetric_matrix() {
        let a = [[2.0, 1.0, 0.5], [1.0, 3.0, 0.25], [0.5, 0.25, 1.0]];
        let (eval, evec) = super::jacobi3(&a, super::Sort::Increasing).unwrap();
        assert!(eval[0] <= eval[1] && eval[1] <= eval[2]);
        for k in 0..3 {
            for r in 0..3 {
                let av: f64 = (0..3).map(|c| a[r][c] * evec[c][k]).sum();
                assert!((av - eval[k] * evec[r][k]).abs() < 1e-12);
            }
        }
    }
}

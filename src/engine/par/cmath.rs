//! The C library's cube root, which LAMMPS calls (`cbrt` in the JKR contact radius and pull-off
//! distance). Rust's `f64::cbrt` is correctly rounded (its own implementation, which also takes
//! the `cbrt` symbol at link time); glibc's is not always: cbrt(23246780.870058574) is
//! 285.40020054889686 in glibc, 285.4002005488968 in Rust, one ulp apart, and a JKR contact in
//! LAMMPS' examples/granular/in.pour.drum went from bit-identical to 1 ulp off through it.
//! glibc exports the same function as `cbrtf64` (the _Float64 alias, glibc 2.27+), a name
//! nothing else defines; elsewhere Rust's is used.

#[cfg(all(target_os = "linux", target_env = "gnu"))]
mod sys {
    extern "C" {
        pub fn cbrtf64(x: f64) -> f64;
    }
}

/// cbrt(x) as the C library computes it (glibc on Linux; Rust's own elsewhere).
#[inline]
pub fn cbrt(x: f64) -> f64 {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        // SAFETY: a pure libm function of one double, defined for every input.
        unsafe { sys::cbrtf64(x) }
    }
    #[cfg(not(all(target_os = "linux", target_env = "gnu")))]
    {
        x.cbrt()
    }
}

#[cfg(test)]
mod tests {
    #[test]
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    fn glibc_cube_root() {
        // glibc's value (Python's math.cbrt gives the same), one ulp above the correctly
        // rounded 285.4002005488968 of f64::cbrt
        assert_eq!(super::cbrt(23246780.870058574), 285.40020054889686);
        // not even exact for every cube (Python's math.cbrt agrees)
        assert_eq!(super::cbrt(27.0), 3.0000000000000004);
        assert_eq!(super::cbrt(-8.0), -2.0);
    }
}

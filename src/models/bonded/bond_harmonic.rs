//! `bond_style harmonic`: E = K (r - r0)^2 (LAMMPS src/MOLECULE/bond_harmonic.cpp).
//!
//! Coefficients: `bond_coeff N K r0` (K in energy/distance^2, the factor 1/2 is folded into K).

use super::{fmt_g, BondStyle, TypeTable, Vec3};
use dmhs_parser::{Args, DResult};

const SYNTAX: &str = "bond_coeff N K r0";

#[derive(Clone, Copy, Debug, PartialEq)]
struct Params {
    k: f64,
    r0: f64,
}

#[derive(Clone, Debug, Default)]
pub struct BondHarmonic {
    types: TypeTable<Params>,
}

impl BondStyle for BondHarmonic {
    fn name(&self) -> &'static str {
        "harmonic"
    }
    fn set_types(&mut self, n: usize) {
        self.types.resize(n);
    }
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()> {
        // LAMMPS: exactly two numbers (utils::numeric), no range checks
        args.syntax = SYNTAX;
        let k = args.f64("K")?;
        let r0 = args.f64("r0")?;
        args.finish()?;
        self.types.set(lo, hi, Params { k, r0 });
        Ok(())
    }
    fn check_all_set(&self) -> Result<(), String> {
        self.types.check_all_set("Bond")
    }
    #[inline(always)]
    fn compute(&self, btype: usize, _del: Vec3, rsq: f64) -> (f64, f64) {
        let p = self.types.get(btype);
        let r = rsq.sqrt();
        let dr = r - p.r0;
        let rk = p.k * dr;
        // LAMMPS: a zero-length bond has no direction, hence no force (its energy stays)
        let fbond = if r > 0.0 { -2.0 * rk / r } else { 0.0 };
        (fbond, rk * dr)
    }
    fn equilibrium_distance(&self, btype: usize) -> f64 {
        self.types.get(btype).r0
    }
    fn stiffness(&self, btype: usize) -> f64 {
        self.types.try_get(btype).map(|p| p.k).unwrap_or(0.0)
    }
    fn coeff_words(&self, btype: usize) -> String {
        let p = self.types.get(btype);
        format!("{} {}", fmt_g(p.k), fmt_g(p.r0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::bonded::bond_virial;
    use crate::models::bonded::test_util::{bits3, bits6, words};
    use dmhs_parser::Span;

    /// One bond alone in real LAMMPS 22 Jul 2025 (`run 0`, pair_style zero):
    /// coefficients, positions of atoms 1 and 2, their forces, ebond and the bond virial.
    struct Case {
        coeff: &'static str,
        x: [[f64; 3]; 2],
        f: [[f64; 3]; 2],
        e: f64,
        v: [f64; 6],
    }

    fn style(coeff: &str) -> BondHarmonic {
        let mut s = BondHarmonic::default();
        s.set_types(1);
        let w = words(coeff);
        s.coeff(1, 1, &mut Args::from_words(&w, Span::default(), "")).unwrap();
        s
    }

    #[test]
    fn matches_lammps_bit_for_bit() {
        for (n, c) in CASES.iter().enumerate() {
            let s = style(c.coeff);
            let [x1, x2] = c.x;
            let del = [x1[0] - x2[0], x1[1] - x2[1], x1[2] - x2[2]];
            let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
            let (fbond, e) = s.compute(1, del, rsq);
            // as LAMMPS accumulates into zeroed forces: f1 += del*fbond, f2 -= del*fbond
            let f1 = del.map(|d| 0.0 + d * fbond);
            let f2 = del.map(|d| 0.0 - d * fbond);
            assert_eq!(bits3(f1), bits3(c.f[0]), "case {n}: f1 {f1:?} vs {:?}", c.f[0]);
            assert_eq!(bits3(f2), bits3(c.f[1]), "case {n}: f2");
            assert_eq!(e.to_bits(), c.e.to_bits(), "case {n}: energy {e} vs {}", c.e);
            let v = bond_virial(del, fbond).map(|x| 0.0 + x);
            assert_eq!(bits6(v), bits6(c.v), "case {n}: virial {v:?} vs {:?}", c.v);
        }
    }

    #[test]
    fn coefficient_errors_point_at_the_word() {
        let mut s = BondHarmonic::default();
        s.set_types(2);
        let w = words("100 abc");
        let e = s.coeff(1, 1, &mut Args::from_words(&w, Span::default(), "")).unwrap_err();
        assert!(e.message.contains("expected a number for r0, found `abc`"), "{e}");
        assert_eq!(e.primary_span().unwrap().lo, 4);
        assert_eq!(e.help, vec![format!("syntax: {SYNTAX}")]);
        let w = words("100 1.0 2");
        assert!(s.coeff(1, 1, &mut Args::from_words(&w, Span::default(), "")).is_err());
        let w = words("100");
        assert!(s.coeff(1, 1, &mut Args::from_words(&w, Span::default(), "")).is_err());
        assert!(s.check_all_set().is_err());
    }

    #[test]
    fn write_data_words_and_ranges() {
        // LAMMPS write_data printed `1 1.5 0.00225` after `bond_coeff * 1.5 2.25e-3`
        let mut s = BondHarmonic::default();
        s.set_types(3);
        let w = words("1.5 2.25e-3");
        s.coeff(1, 3, &mut Args::from_words(&w, Span::default(), "")).unwrap();
        assert!(s.check_all_set().is_ok());
        assert_eq!(s.coeff_words(3), "1.5 0.00225");
        assert_eq!(s.equilibrium_distance(2), 2.25e-3);
        // and `1 1.23457e+06 1e-05` after `bond_coeff 1 1234567 1e-5`
        let w = words("1234567 1e-5");
        s.coeff(1, 1, &mut Args::from_words(&w, Span::default(), "")).unwrap();
        assert_eq!(s.coeff_words(1), "1.23457e+06 1e-05");
    }

    #[rustfmt::skip]
    const CASES: &[Case] = &[
    // random
    Case {
        coeff: "423.8694347316791 1.2637746189766141",
        x: [[0.5774467022710263, -0.8122808264515302, -0.9433050469559874], [0.4505710091265833, -1.3706544601564297, -0.77940752908334]],
        f: [[120.66295749863052, 531.0316922200877, -155.87193057289292], [-120.66295749863052, -531.0316922200877, 155.87193057289292]],
        e: 189.23885511942728,
        v: [15.309196369497217, 296.51409559739216, 25.54702252691477, 67.37501403209018, -19.77635923319829, -87.03477626658402],
    },
    // random
    Case {
        coeff: "216.95076688462163 1.2622800824579419",
        x: [[0.8905413911078446, 0.8028549152229671, -0.9388200339328929], [1.7209044849738868, -1.1410908857565671, -0.6139542037881991]],
        f: [[147.64430093451256, -345.64700786967603, 57.76339139292392], [-147.64430093451256, 345.64700786967603, -57.76339139292392]],
        e: 166.63608189711738,
        v: [-122.59837851567084, -671.9190495693967, -18.76535209683509, 287.01251884020445, -47.96458838922342, 112.28890214861181],
    },
    // random
    Case {
        coeff: "271.16482392395477 1.4391491627785107",
        x: [[-0.5566166674539299, -0.12422481269885588, -0.008375517236298702], [-0.2773297920515727, -0.3326816604839473, -0.08094948546651566]],
        f: [[-460.87496054379534, 343.99232459323474, 119.7604602666037], [460.87496054379534, -343.99232459323474, -119.7604602666037]],
        e: 318.145078226799,
        v: [128.71632768146125, 71.7075556469717, 8.691491838624657, -96.07254149803796, -33.4475247446079, 24.964888036467897],
    },
    // random
    Case {
        coeff: "116.20240422895117 0.7187810373376886",
        x: [[0.11290864530486688, 0.28458872586489115, -0.6281874682105646], [-0.4423264286006712, 0.3549371453778861, -0.03879298747274307]],
        f: [[-14.924359884415273, 1.8909200435172415, 15.842542659536367], [14.924359884415273, -1.8909200435172415, -15.842542659536367]],
        e: 1.0268682856796532,
        v: [-8.286528063416162, -0.1330232364868816, -9.337507204384224, 1.0499051301117588, 8.796335344419314, -1.1144978371655834],
    },
    // random
    Case {
        coeff: "430.11331786884966 0.6208899598058064",
        x: [[-0.15578600007716958, 0.660071386548654, 0.34061113282814204], [-1.0654175972194886, 1.2892896732057464, -1.8831022809351754]],
        f: [[-586.8698058112698, 405.9546907379171, -1434.6799994800663], [586.8698058112698, -405.9546907379171, 1434.6799994800663]],
        e: 1492.352116376508,
        v: [-533.835318774708, -255.43411496652195, -3190.3171593017723, 369.2692137033477, -1305.030259315194, 902.7268911740454],
    },
    // random
    Case {
        coeff: "294.20272246563616 1.3824790008318577",
        x: [[-0.5145200529138647, 0.5948084951086057, -0.17137200139845143], [0.36088754572565407, 0.7578632716880724, 0.20672611429433607]],
        f: [[-221.00171279652952, -41.164121672830596, -95.45305672821267], [221.00171279652952, 41.164121672830596, 95.45305672821267]],
        e: 50.68573763607995,
        v: [193.46657869443052, 6.712006662453379, 36.09062088605397, 36.0353849037176, 83.56033117324641, 15.564076838645883],
    },
    // coincident atoms: r = 0, no force
    Case {
        coeff: "100.0 1.0",
        x: [[0.5, 0.25, 0.125], [0.5, 0.25, 0.125]],
        f: [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        e: 100.0,
        v: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    },
    // at rest length
    Case {
        coeff: "30 1.5",
        x: [[0.0, 0.0, 0.0], [1.5, 0.0, 0.0]],
        f: [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        e: 0.0,
        v: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    },
    // negative k, r0 = 0
    Case {
        coeff: "-7.5 0.0",
        x: [[-0.25059395899671943, -0.12207673991087375, 0.016852976499963646], [-0.40378865617730075, -0.7450421472322103, -0.6143724079996711]],
        f: [[2.2979204577087198, 9.344481109820048, 9.468380767494521], [-2.2979204577087198, -9.344481109820048, -9.468380767494521]],
        e: -6.075000000000003,
        v: [0.35202922866375014, 5.821288480785581, 5.976682290550675, 1.4315249539285446, 1.4505057244667632, 5.898473681495733],
    },
    ];
}

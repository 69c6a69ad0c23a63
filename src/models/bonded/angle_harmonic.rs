//! `angle_style harmonic`: E = K (theta - theta0)^2 (LAMMPS src/MOLECULE/angle_harmonic.cpp).
//!
//! Coefficients: `angle_coeff N K theta0`, theta0 in degrees, stored as `DEG2RAD * theta0`
//! exactly as LAMMPS does (so `write_data` prints `RAD2DEG * theta0`, which may differ from
//! the input in the last digit before `%g` rounding).

use super::pass::{apply_angles_in_lanes, BondedTally, Kernels};
use super::{fmt_g, AngleForces, AngleStyle, TypeTable, Vec3, DEG2RAD, RAD2DEG};
use crate::engine::bonded_lists::Entry;
use crate::engine::par::lanes::{lanes, Real};
use crate::engine::par::AtomsMut;
use dmhs_parser::{Args, DResult};

const SYNTAX: &str = "angle_coeff N K theta0";

/// Lower bound of sin(theta) in the force prefactor: keeps the force finite for a straight
/// (or folded) angle, where dE/dtheta / sin(theta) is 0/0.
const SMALL: f64 = 0.001;

#[derive(Clone, Copy, Debug, PartialEq)]
struct Params {
    k: f64,
    /// radians
    theta0: f64,
}

#[derive(Clone, Debug, Default)]
pub struct AngleHarmonic {
    types: TypeTable<Params>,
}

impl AngleStyle for AngleHarmonic {
    fn name(&self) -> &'static str {
        "harmonic"
    }
    fn set_types(&mut self, n: usize) {
        self.types.resize(n);
    }
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()> {
        // LAMMPS: exactly two numbers, no range checks
        args.syntax = SYNTAX;
        let k = args.f64("K")?;
        let theta0_deg = args.f64("theta0 (degrees)")?;
        args.finish()?;
        self.types.set(lo, hi, Params { k, theta0: DEG2RAD * theta0_deg });
        Ok(())
    }
    fn check_all_set(&self) -> Result<(), String> {
        self.types.check_all_set("Angle")
    }
    #[inline(always)]
    fn compute(&self, atype: usize, del1: Vec3, del2: Vec3) -> AngleForces {
        let p = self.types.get(atype);
        let (f1, f3, energy) = kernel(p.k, p.theta0, del1, del2);
        AngleForces { f1, f3, energy }
    }
    fn apply(&self, entries: &[Entry<3>], k: &Kernels, f: &mut AtomsMut<Vec3>, t: &mut BondedTally) {
        apply_angles_in_lanes(entries, k, f, t, |typ, del1, del2| {
            let p = typ.map(|t| self.types.get(t));
            kernel(lanes(|l| p[l].k), lanes(|l| p[l].theta0), del1, del2)
        })
    }
    fn equilibrium_angle(&self, atype: usize) -> f64 {
        self.types.get(atype).theta0
    }
    fn coeff_words(&self, atype: usize) -> String {
        let p = self.types.get(atype);
        format!("{} {}", fmt_g(p.k), fmt_g(RAD2DEG * p.theta0))
    }
}

/// LAMMPS' angle_harmonic force on atoms 1 and 3 and the energy, for one angle (`f64`) or
/// four (`L`, lane by lane the same operations): `del1 = x1 - x2`, `del2 = x3 - x2`.
#[inline(always)]
fn kernel<R: Real>(k: R, theta0: R, del1: [R; 3], del2: [R; 3]) -> ([R; 3], [R; 3], R) {
    let rsq1 = del1[0] * del1[0] + del1[1] * del1[1] + del1[2] * del1[2];
    let r1 = rsq1.sqrt();
    let rsq2 = del2[0] * del2[0] + del2[1] * del2[1] + del2[2] * del2[2];
    let r2 = rsq2.sqrt();

    // cosine, clamped against rounding (a NaN stays NaN, as with f64::clamp); 1/sin with sin
    // bounded below by SMALL
    let c = del1[0] * del2[0] + del1[1] * del2[1] + del1[2] * del2[2];
    let c = c / (r1 * r2);
    let (one, minus_one) = (R::splat(1.0), R::splat(-1.0));
    let c = R::select(c.lt(minus_one), minus_one, c);
    let c = R::select(one.lt(c), one, c);
    let s = (one - c * c).sqrt();
    let small = R::splat(SMALL);
    let s = R::select(s.lt(small), small, s);
    let s = one / s;

    let dtheta = c.map(f64::acos) - theta0;
    let tk = k * dtheta;
    let energy = tk * dtheta;

    let a = R::splat(-2.0) * tk * s;
    let a11 = a * c / rsq1;
    let a12 = -a / (r1 * r2);
    let a22 = a * c / rsq2;
    let f1 = [a11 * del1[0] + a12 * del2[0], a11 * del1[1] + a12 * del2[1], a11 * del1[2] + a12 * del2[2]];
    let f3 = [a22 * del2[0] + a12 * del1[0], a22 * del2[1] + a12 * del1[1], a22 * del2[2] + a12 * del1[2]];
    (f1, f3, energy)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::bonded::angle_virial;
    use crate::models::bonded::test_util::{bits3, bits6, words};
    use dmhs_parser::Span;

    /// One angle alone in real LAMMPS 22 Jul 2025 (`run 0`, pair_style zero):
    /// coefficients, positions of atoms 1-3, their forces, eangle and the angle virial.
    struct Case {
        coeff: &'static str,
        x: [[f64; 3]; 3],
        f: [[f64; 3]; 3],
        e: f64,
        v: [f64; 6],
    }

    fn style(coeff: &str) -> AngleHarmonic {
        let mut s = AngleHarmonic::default();
        s.set_types(1);
        let w = words(coeff);
        s.coeff(1, 1, &mut Args::from_words(&w, Span::default(), "")).unwrap();
        s
    }

    fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }

    #[test]
    fn matches_lammps_bit_for_bit() {
        for (n, c) in CASES.iter().enumerate() {
            let s = style(c.coeff);
            let del1 = sub(c.x[0], c.x[1]);
            let del2 = sub(c.x[2], c.x[1]);
            let out = s.compute(1, del1, del2);
            let f2 = out.f2().map(|x| 0.0 + x);
            assert_eq!(bits3(out.f1.map(|x| 0.0 + x)), bits3(c.f[0]), "case {n}: f1 {:?} vs {:?}", out.f1, c.f[0]);
            assert_eq!(bits3(f2), bits3(c.f[1]), "case {n}: f2 {f2:?} vs {:?}", c.f[1]);
            assert_eq!(bits3(out.f3.map(|x| 0.0 + x)), bits3(c.f[2]), "case {n}: f3");
            assert_eq!(out.energy.to_bits(), c.e.to_bits(), "case {n}: energy {} vs {}", out.energy, c.e);
            let v = angle_virial(del1, del2, out.f1, out.f3).map(|x| 0.0 + x);
            assert_eq!(bits6(v), bits6(c.v), "case {n}: virial {v:?} vs {:?}", c.v);
        }
    }

    #[test]
    fn theta0_is_stored_in_radians_like_lammps() {
        let s = style("1 109.47");
        assert_eq!(s.equilibrium_angle(1).to_bits(), (DEG2RAD * 109.47).to_bits());
        // LAMMPS write_data printed `1 1 109.47`
        assert_eq!(s.coeff_words(1), "1 109.47");
    }

    #[test]
    fn coefficient_errors() {
        let mut s = AngleHarmonic::default();
        s.set_types(1);
        let w = words("1 x");
        let e = s.coeff(1, 1, &mut Args::from_words(&w, Span::default(), "")).unwrap_err();
        assert!(e.message.contains("found `x`"), "{e}");
        let w = words("1 2 3");
        assert!(s.coeff(1, 1, &mut Args::from_words(&w, Span::default(), "")).is_err());
        assert!(s.check_all_set().is_err());
    }

    #[rustfmt::skip]
    const CASES: &[Case] = &[
    // random, theta 168.185
    Case {
        coeff: "284.8699712472113 66.78616412721705",
        x: [[0.21754820945804632, -0.2208479673251792, 0.08597670382799139], [0.21360346728167579, 0.16240803422400618, -0.6832342594903889], [0.3335290420719402, 0.5398729078872639, -2.0102404663676654]],
        f: [[521.9708039151508, -939.3941231131423, -470.7258385737723], [-839.7175883009937, 1576.4936402492442, 623.2320755021628], [317.74678438584294, -637.0995171361019, -152.50623692839054]],
        e: 892.2160240230347,
        v: [40.16500600026855, 119.54574675644488, -159.710752756713, -80.11019340882594, -20.146290191666825, 122.84275526263748],
    },
    // random, theta 86.754
    Case {
        coeff: "124.12422785955769 146.76144974849592",
        x: [[-0.17820740379779987, 1.0031851096169018, 0.34319667484843885], [-0.945110285818362, -0.07021227580537581, -0.36306974429264516], [0.348033468918471, -0.7055880323915404, -0.6258665705934766]],
        f: [[-148.60994751091098, 82.56909354317688, 35.87873815086012], [230.84865152253306, 49.347814768929254, 49.851601070122264], [-82.23870401162208, -131.91690831210613, -85.73033922098239]],
        e: 136.15218442000906,
        v: [-220.3158635333221, 172.44625455124566, 47.86960898207644, -107.26505032390372, -83.34614506392782, 92.98312286830401],
    },
    // random, theta 78.902
    Case {
        coeff: "268.6189427702034 123.09033229752339",
        x: [[0.20175724084358304, 0.8214435730422891, 0.11567064601869437], [0.997367136385104, 0.3489593946917402, -0.6363130063537112], [0.7178659352158543, 1.1307870771841295, -1.1286567465011128]],
        f: [[57.053479803776476, -259.8012613662997, 223.60100261166968], [-324.54130541793853, 364.9378360280458, 95.20441781126016], [267.48782561416203, -105.13657466174612, -318.80542042292984]],
        e: 159.77191577970183,
        v: [-120.15548166427196, -204.95067002407336, 325.1061516883453, 236.08625332197562, -88.79267238337333, -143.6029670179374],
    },
    // random, theta 158.504
    Case {
        coeff: "241.06037721227545 148.12820302727732",
        x: [[0.026331119483382626, 1.7577248352331074, 0.40259355999909396], [-0.6776306933919622, 0.5080081433037442, 0.43030179647490696], [-1.6971593319682305, -0.3450398925544734, 0.3185908585973933]],
        f: [[-51.098327392376476, 28.409034185882064, -16.891257686321953], [90.4596796613457, -77.72612223541661, 34.25588858509751], [-39.36135226896923, 49.31708804953455, -17.36463089877555]],
        e: 7.904766051258086,
        v: [4.158754705267867, -6.566600871213495, 2.407846165945573, -30.28130843015672, 5.812938117000234, -6.296422396673298],
    },
    // random, theta 91.518
    Case {
        coeff: "163.80315767579904 118.80167062202295",
        x: [[-0.38778878090327007, 0.16255611609947748, -0.5729143373029117], [-0.07797567023672469, 0.13541014084048864, 0.8406608783838576], [-0.8612093650117016, -0.686415334067693, 1.0277499630888327]],
        f: [[74.00737131931206, 76.95879155546564, -14.742287667401724], [-105.48555118334426, -76.98142240034342, -117.13803962932151], [31.478179864032203, 0.022630844877786327, 131.88032729672324]],
        e: 37.1433769722314,
        v: [-47.58322504038736, 2.0705228466870897, 45.512702193700285, -23.86056784518658, -98.72576201616701, -108.78280638795619],
    },
    // random, theta 132.185
    Case {
        coeff: "151.11648090985966 86.6173213189213",
        x: [[-0.8307780960492674, 0.07759847138652431, 0.022430165596156293], [-0.3808737501010786, 0.914723423112316, 0.4124116127352093], [-0.39107967487559925, 1.4327985450361145, 1.5934367925726376]],
        f: [[-95.37013712382264, -45.95410872828985, 208.66831182212104], [206.86429513998007, 183.072373631696, -267.8538922920669], [-111.49415801615743, -137.11826490340616, 59.18558046994589]],
        e: 95.58213222636434,
        v: [44.045340155193934, -32.56823075704041, -11.477109398153502, 22.074371927850162, -94.48482393245669, -144.01887364269754],
    },
    // near linear: sin < SMALL clamps
    Case {
        coeff: "50 180",
        x: [[-0.2790980021628639, -1.4097915179649132, 0.5798565228861811], [-0.3763113508979996, -0.5843630509241455, 0.023783316710564995], [-0.49313379782343125, 0.4062080676743197, -0.6433908546217337]],
        f: [[0.002420629433406374, -0.0008286421287717616, -0.0016532037241390185], [-0.004437777527000586, 0.0015188115210680309, 0.003031119840436247], [0.002017148093594212, -0.0006901693922962693, -0.0013779161162972287]],
        e: 1.5230871047464676e-06,
        v: [-3.306828363776836e-07, 3.2293512813516556e-07, 7.7477125701381e-09, 7.220096017384421e-08, 2.580621988783956e-07, -3.2249293324053234e-07],
    },
    // nearly exactly linear
    Case {
        coeff: "50 109.47",
        x: [[0.7269615266837894, 0.7577742717918858, 0.3425087175854621], [0.4518985749545963, 0.8153072419026417, -0.617194533391765], [0.1218230313182529, 0.8843468073290461, -1.7688384340394026]],
        f: [[-0.00016016204608604312, 0.00013268919701658888, 5.3858995670452714e-05], [0.0002936304153990932, -0.00024326352831849363, -9.874148236121982e-05], [-0.00013346836931305006, 0.00011057433130190475, 4.488248669076711e-05]],
        e: 75.7656768268132,
        v: [-5.921528323021494e-13, 1.7442316918602797e-13, 1.1195981153896278e-11, -3.2274196878380457e-13, 3.1320786570999135e-12, -6.11716543067744e-13],
    },
    // exactly linear: c = -1
    Case {
        coeff: "40 120",
        x: [[-1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
        f: [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        e: 43.86490844928605,
        v: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    },
    // near zero angle
    Case {
        coeff: "40 60",
        x: [[-1.227580177245004, 1.189937968246454, -0.20111379278493258], [-0.5467669415104739, 0.7509823428964757, -0.7874680347089502], [-1.2957382461556277, 1.2339195431098524, -0.1426318962456955]],
        f: [[5.844805617351085, -6.550151836621808, 11.689941898774123], [-0.5329252429146436, 0.5964866295907996, -1.0613620605290635], [-5.311880374436441, 5.953665207031008, -10.62857983824506]],
        e: 43.850288031737875,
        v: [-0.0007750504274994796, 2.041050971524072e-05, 0.0007546399491635825, 0.00030566891249339534, 0.0018341383225140007, -0.0015708328451067288],
    },
    // exactly folded: c = 1
    Case {
        coeff: "40 60",
        x: [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
        f: [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        e: 43.86490844928603,
        v: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    },
    // at rest angle 90
    Case {
        coeff: "25 90",
        x: [[0.0, 1.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
        f: [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        e: 0.0,
        v: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    },
    ];
}

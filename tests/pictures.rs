//! `dump image` / `dump movie` and `dmhs plot`: the PNG files are decoded back and the pixels
//! checked against the positions and colours the deck asks for; errors point at file:line:col;
//! the camera matches LAMMPS' (blob centres in LAMMPS' own PPM images, when LAMMPS is installed).

use dmhs::deck::{run_text, DeckOptions};
use dmhs::output::render::decode_png;
use std::path::Path;

fn run_in(dir: &Path, deck: &str) -> Result<dmhs::deck::DeckRun, String> {
    let opts = DeckOptions { base_dir: Some(dir.to_path_buf()), ..Default::default() };
    run_text("in.picture", deck, &opts).map_err(|f| f.rendered)
}

struct Image {
    w: usize,
    h: usize,
    rgb: Vec<u8>,
}

impl Image {
    fn read(path: &Path) -> Image {
        let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
        let (w, h, rgb) = decode_png(&bytes).unwrap();
        Image { w, h, rgb }
    }
    fn px(&self, x: usize, y: usize) -> [u8; 3] {
        let k = 3 * (y * self.w + x);
        [self.rgb[k], self.rgb[k + 1], self.rgb[k + 2]]
    }
}

fn close(a: [u8; 3], b: [u8; 3], tol: i32) -> bool {
    (0..3).all(|k| (a[k] as i32 - b[k] as i32).abs() <= tol)
}

/// Three atoms of types 1..3 in a 10 x 5 box (2d), imaged 400 x 200: one pixel is
/// 2 * 10 / 200 = 0.1 length units, the box centre (5, 2.5) is the image centre.
const THREE_ATOMS: &str = "
units lj
dimension 2
boundary p p p
atom_style atomic
region box block 0 10 0 5 -0.5 0.5
create_box 3 box
create_atoms 1 single 2 2 0
create_atoms 2 single 7 3 0
create_atoms 3 single 5 4.5 0
mass * 1
set atom 1 vx 0.0
set atom 2 vx 1.0
set atom 3 vx 2.0
";

/// Pixel under (x, y) for the THREE_ATOMS camera.
fn at(x: f64, y: f64) -> (usize, usize) {
    ((200.0 + (x - 5.0) / 0.1) as usize, (100.0 - (y - 2.5) / 0.1) as usize)
}

#[test]
fn colours_by_type_at_the_atom_positions() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = format!("{THREE_ATOMS}dump 1 all image 10 img.*.png type type size 400 200\nvariable z equal 2.0\ndump 2 all image 20 zoom.*.png type type size 400 200 zoom v_z center d 0.2 0.4 0.5\nrun 20\n");
    run_in(tmp.path(), &deck).unwrap();
    // zoom 2 through a variable, centred on (2, 2): the type-1 atom at the image centre
    // (LAMMPS' pixel grid: centre pixel (W/2, H/2 - 1)) and the type-2 atom 5 / 0.05 = 100 pixels right
    let im = Image::read(&tmp.path().join("zoom.20.png"));
    assert!(close(im.px(200, 99), [255, 0, 0], 3), "{:?}", im.px(200, 99));
    assert!(close(im.px(300, 79), [34, 139, 34], 3), "{:?}", im.px(300, 79));
    for step in [0, 10, 20] {
        assert!(tmp.path().join(format!("img.{step}.png")).exists());
    }
    let im = Image::read(&tmp.path().join("img.0.png"));
    assert_eq!((im.w, im.h), (400, 200));
    // LAMMPS' default type colours: red, forestgreen, blue; background black
    let (x, y) = at(2.0, 2.0);
    assert!(close(im.px(x, y), [255, 0, 0], 3), "{:?}", im.px(x, y));
    let (x, y) = at(7.0, 3.0);
    assert!(close(im.px(x, y), [34, 139, 34], 3), "{:?}", im.px(x, y));
    let (x, y) = at(5.0, 4.5);
    assert!(close(im.px(x, y), [0, 0, 255], 3), "{:?}", im.px(x, y));
    // diameter 1 = 10 pixels: 6 pixels from a centre is background
    let (x, y) = at(2.0, 2.0);
    assert_eq!(im.px(x + 6, y), [0, 0, 0]);
    assert_eq!(im.px(5, 5), [0, 0, 0]);
    // the box outline (gold) at x = 0 and y = 5
    let (x, y) = at(0.0, 1.0);
    assert!(close(im.px(x, y), [255, 215, 0], 0) || close(im.px(x - 1, y), [255, 215, 0], 0), "{:?}", im.px(x, y));
    let (x, y) = at(3.0, 5.0);
    assert!(close(im.px(x, y), [255, 215, 0], 0) || close(im.px(x, y - 1), [255, 215, 0], 0));
    // about pi * 5^2 = 79 pixels per atom are red / green / blue
    let n_red = (0..im.h).flat_map(|y| (0..im.w).map(move |x| (x, y))).filter(|&(x, y)| im.px(x, y)[0] > 50 && im.px(x, y)[1] < 10).count();
    assert!((70..=90).contains(&n_red), "{n_red} red pixels");
}

#[test]
fn colours_by_per_atom_value_through_amap() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = format!(
        "{THREE_ATOMS}compute p all property/atom vx
dump 1 all image 100 vx.*.png vx type size 400 200 box no 0.0
dump 2 all image 100 seq.*.png c_p 2.0 size 400 200
dump_modify 2 amap 0 2 sa 1 2 red green backcolor white acolor * white
dump 3 all image 100 cont.*.png vx type size 400 200 adiam 1.0
dump_modify 3 amap 0 4 ca 0 3 min black 2.0 white max black
run 0
"
    );
    run_in(tmp.path(), &deck).unwrap();
    // default map: min blue, max red, linear in between (vx = 0, 1, 2)
    let im = Image::read(&tmp.path().join("vx.0.png"));
    let (x, y) = at(2.0, 2.0);
    assert!(close(im.px(x, y), [0, 0, 255], 3), "{:?}", im.px(x, y));
    let (x, y) = at(7.0, 3.0);
    assert!(close(im.px(x, y), [128, 0, 128], 3), "{:?}", im.px(x, y));
    let (x, y) = at(5.0, 4.5);
    assert!(close(im.px(x, y), [255, 0, 0], 3), "{:?}", im.px(x, y));
    // sequential bins of width 1 over 0..2: red, green, red; diameter 2 (20 pixels); white background
    let im = Image::read(&tmp.path().join("seq.0.png"));
    let (x, y) = at(2.0, 2.0);
    assert!(close(im.px(x, y), [255, 0, 0], 3));
    assert!(close(im.px(x + 8, y), [255, 0, 0], 150) && im.px(x + 8, y) != [255, 255, 255]);
    let (x, y) = at(7.0, 3.0);
    assert!(close(im.px(x, y), [0, 128, 0], 3), "{:?}", im.px(x, y));
    let (x, y) = at(5.0, 4.5);
    assert!(close(im.px(x, y), [255, 0, 0], 3));
    assert_eq!(im.px(5, 5), [255, 255, 255]);
    // absolute continuous map 0..4: black at 0, white at 2, black at 4 -> vx 1 is mid grey
    let im = Image::read(&tmp.path().join("cont.0.png"));
    let (x, y) = at(7.0, 3.0);
    assert!(close(im.px(x, y), [128, 128, 128], 3), "{:?}", im.px(x, y));
    let (x, y) = at(5.0, 4.5);
    assert!(close(im.px(x, y), [255, 255, 255], 3), "{:?}", im.px(x, y));
}

#[test]
fn bonds_are_drawn_in_halves_across_the_periodic_boundary() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(
        tmp.path().join("pair.data"),
        "two bonded atoms across the x boundary

2 atoms
1 bonds
2 atom types
1 bond types

0 10 xlo xhi
0 5 ylo yhi
-0.5 0.5 zlo zhi

Masses

1 1
2 1

Atoms # bond

1 1 1 0.5 2.5 0
2 1 2 9.5 2.5 0

Bonds

1 1 1 2
",
    )
    .unwrap();
    let deck = "units lj\ndimension 2\natom_style bond\nread_data pair.data\nbond_style harmonic\nbond_coeff 1 1.0 1.0\n\
dump 1 all image 1 b.*.png type type size 400 200 adiam 0.4 bond atom 0.3 box no 0.0\nrun 0\n";
    run_in(tmp.path(), deck).unwrap();
    let im = Image::read(&tmp.path().join("b.0.png"));
    // the bond leaves atom 1 toward -x (the minimum image), red half; atom 2 toward +x, green
    // (cylinders are shaded across their width: the colour within 15%)
    let (x, y) = at(0.1, 2.5);
    assert!(close(im.px(x, y), [255, 0, 0], 40), "{:?}", im.px(x, y));
    let (x, y) = at(9.9, 2.5);
    assert!(close(im.px(x, y), [34, 139, 34], 21), "{:?}", im.px(x, y));
    // nothing is drawn across the box interior
    let (x, y) = at(5.0, 2.5);
    assert_eq!(im.px(x, y), [0, 0, 0]);
}

#[test]
fn movie_frames_are_numbered_pngs_and_writes_leave_no_temporary_files() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = format!("{THREE_ATOMS}dump m all movie 5 film.mp4 type type size 64 32\ndump_modify m framerate 10\ndump p all image 5 pad.*.ppm type type size 64 32\ndump_modify p pad 4\nrun 10\n");
    let r = run_in(tmp.path(), &deck).unwrap();
    drop(r);
    let mut names: Vec<String> = std::fs::read_dir(tmp.path()).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().to_string()).collect();
    names.sort();
    assert_eq!(
        names,
        ["film.0000000000.png", "film.0000000005.png", "film.0000000010.png", "pad.0000.ppm", "pad.0005.ppm", "pad.0010.ppm"].map(String::from).to_vec()
    );
    let im = Image::read(&tmp.path().join("film.0000000005.png"));
    assert_eq!((im.w, im.h), (64, 32));
    let ppm = std::fs::read(tmp.path().join("pad.0010.ppm")).unwrap();
    assert!(ppm.starts_with(b"P6\n64 32\n255\n") && ppm.len() == 13 + 64 * 32 * 3);
}

#[test]
fn a_3d_view_puts_the_box_centre_at_the_image_centre() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = "units lj\nregion box block 0 4 0 4 0 4\ncreate_box 2 box\ncreate_atoms 1 single 2 2 2\ncreate_atoms 2 single 2 2 3.5\nmass * 1\n\
dump 1 all image 1 v.*.png type type size 300 300 box no 0.0\ndump 2 all image 1 top.*.png type type size 300 300 view 0 0 up 0 1 0 box no 0.0 fsaa yes\nrun 0\n";
    run_in(tmp.path(), deck).unwrap();
    let im = Image::read(&tmp.path().join("v.0.png"));
    // default view 60 30: the centre atom is at the centre; the higher (z = 3.5) atom is
    // above it on the image (up = z), at 1.5 sin(60 deg) / (2 * 4 / 300) = 48.7 pixels
    assert!(close(im.px(150, 150), [255, 0, 0], 3), "{:?}", im.px(150, 150));
    assert!(close(im.px(150, 150 - 49), [34, 139, 34], 3), "{:?}", im.px(150, 101));
    // from the top the type-2 atom (nearer the viewer) hides the type-1 atom under it
    let im = Image::read(&tmp.path().join("top.0.png"));
    assert!(close(im.px(150, 150), [34, 139, 34], 3), "{:?}", im.px(150, 150));
}

#[test]
fn bad_image_commands_are_errors_with_file_line_col() {
    let tmp = tempfile::tempdir().unwrap();
    let cases: &[(&str, &str, &str)] = &[
        ("dump 1 all image 1 a.*.png type type sizee 10 10", "in.picture:15:38", "unknown keyword `sizee`"),
        ("dump 1 all image 1 a.*.png type type ssao yes 1 0.5", "in.picture:15:38", "`ssao` is a LAMMPS option that dmhs does not support"),
        ("dump 1 all image 1 a.png type type", "in.picture:15:20", "must contain *"),
        ("dump 1 all image 1 a.*.jpg type type", "in.picture:15:20", "not JPEG"),
        ("dump 1 all image 1 a.*.png nosuch type", "in.picture:15:28", "unknown dump field `nosuch`"),
        ("dump 1 all image 1 a.*.png type type\ndump_modify 1 acolor 1 notacolor", "in.picture:16:24", "unknown color `notacolor`"),
        ("dump 1 all image 1 a.*.png vx type\ndump_modify 1 amap min max cf 0.0 2 0.5 blue max red", "in.picture:16:37", "from min (first entry) to max"),
        ("dump 1 all image 1 a.*.png vx type\ndump_modify 1 bitrate 100", "in.picture:16:15", "bitrate is a LAMMPS image option"),
        ("dump 1 all image 1 a.*.png vx type\ndump_modify 1 acolr 1 red", "in.picture:16:15", "unknown keyword `acolr`"),
        ("dump 1 all image 1 a.*.png type type view 60 30", "in.picture:15:38", "viewed along z"),
        ("dump 1 all movie 1 a.*.mp4 type type", "in.picture:15:20", "must not contain *"),
    ];
    for (line, at, msg) in cases {
        let deck = format!("{THREE_ATOMS}{line}\n");
        let err = run_in(tmp.path(), &deck).err().unwrap_or_else(|| panic!("`{line}` should fail"));
        assert!(err.contains(at) && err.contains(msg), "`{line}`: expected {at} and `{msg}` in\n{err}");
        println!("{err}");
    }
    // nothing was written by the failed decks
    assert_eq!(std::fs::read_dir(tmp.path()).unwrap().count(), 0);
}

/// Bounding-box centres of the pixels that are neither background nor box colour, per
/// colour class (the reddest, greenest, bluest blobs), from raw RGB rows.
fn blob_centres(w: usize, h: usize, rgb: &[u8]) -> [(f64, f64); 3] {
    let mut out = [(0.0, 0.0); 3];
    for (c, o) in out.iter_mut().enumerate() {
        let (mut x0, mut x1, mut y0, mut y1) = (usize::MAX, 0, usize::MAX, 0);
        for y in 0..h {
            for x in 0..w {
                let p = &rgb[3 * (y * w + x)..3 * (y * w + x) + 3];
                let (a, b1, b2) = (p[c] as i32, p[(c + 1) % 3] as i32, p[(c + 2) % 3] as i32);
                // dominant channel c, clearly above the others
                if a > 25 && a > b1 + 15 && a > b2 + 15 {
                    x0 = x0.min(x);
                    x1 = x1.max(x);
                    y0 = y0.min(y);
                    y1 = y1.max(y);
                }
            }
        }
        assert!(x0 <= x1, "no blob of channel {c}");
        *o = (0.5 * (x0 + x1) as f64, 0.5 * (y0 + y1) as f64);
    }
    out
}

fn read_ppm(path: &Path) -> (usize, usize, Vec<u8>) {
    let b = std::fs::read(path).unwrap();
    let text = String::from_utf8_lossy(&b[..20.min(b.len())]).to_string();
    let mut it = text.split_whitespace();
    assert_eq!(it.next(), Some("P6"));
    let w: usize = it.next().unwrap().parse().unwrap();
    let h: usize = it.next().unwrap().parse().unwrap();
    (w, h, b[b.len() - w * h * 3..].to_vec())
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn camera_matches_lammps() {
    let lmp = match dmhs::tools::lammps::find_python().and_then(|p| dmhs::tools::lammps::find_lmp(&p).map(|l| (p, l))) {
        Ok(x) => x,
        Err(e) => {
            assert!(!dmhs::tools::lammps::live_tests_required(), "DMHS_REQUIRE_LAMMPS=1 but LAMMPS is not available: {e}");
            println!("skipped: {e}");
            return;
        }
    };
    // red (type 1), green (type 3 with acolor), blue (type 2 with acolor): one blob per channel
    let scenes = [
        ("2d", "dimension 2\nregion box block 0 10 0 5 -0.5 0.5\ncreate_box 3 box\ncreate_atoms 1 single 2 2 0\ncreate_atoms 2 single 7 3 0\ncreate_atoms 3 single 5 4.5 0\n", "size 300 200 zoom 1.5 box no 0.0"),
        ("3d", "region box block 0 4 0 6 0 5\ncreate_box 3 box\ncreate_atoms 1 single 1 1 1\ncreate_atoms 2 single 3 5 2\ncreate_atoms 3 single 2 3 4.5\n", "size 300 300 view 70 -20 box no 0.0"),
        ("3dc", "region box block 0 4 0 6 0 5\ncreate_box 3 box\ncreate_atoms 1 single 1 1 1\ncreate_atoms 2 single 3 5 2\ncreate_atoms 3 single 2 3 4.5\n", "size 240 320 view 35 120 up 0 1 0 center s 0.3 0.6 0.5 zoom 0.8 box no 0.0"),
    ];
    for (name, setup, keys) in scenes {
        let tmp = tempfile::tempdir().unwrap();
        let deck = format!("units lj\nboundary p p p\natom_style atomic\n{setup}mass * 1\ndump 1 all image 1 pic.*.ppm type type adiam 0.6 {keys}\ndump_modify 1 acolor 1 red acolor 2 blue acolor 3 green backcolor black\nrun 0\n");
        std::fs::write(tmp.path().join("in.deck"), &deck).unwrap();
        run_in(tmp.path(), &deck.replace("pic.*", "dm.*")).unwrap();
        let o = std::process::Command::new(&lmp.1)
            .args(["-in", "in.deck", "-log", "none", "-screen", "none"])
            .current_dir(tmp.path())
            .env("LD_LIBRARY_PATH", dmhs::tools::lammps::library_path(&lmp.0))
            .output()
            .unwrap();
        assert!(o.status.success(), "LAMMPS failed: {}", String::from_utf8_lossy(&o.stdout));
        let (w, h, l) = read_ppm(&tmp.path().join("pic.0.ppm"));
        let (w2, h2, d) = read_ppm(&tmp.path().join("dm.0.ppm"));
        assert_eq!((w, h), (w2, h2));
        let (cl, cd) = (blob_centres(w, h, &l), blob_centres(w, h, &d));
        for k in 0..3 {
            let (dx, dy) = (cl[k].0 - cd[k].0, cl[k].1 - cd[k].1);
            println!("{name} blob {k}: LAMMPS {:?} dmhs {:?}", cl[k], cd[k]);
            assert!(dx.abs() <= 1.0 && dy.abs() <= 1.0, "{name}: blob {k} LAMMPS {:?} dmhs {:?}", cl[k], cd[k]);
        }
    }
}

#[test]
fn plot_draws_a_log_written_by_a_dmhs_run() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = "units lj\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
velocity all create 1.5 87287\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\n\
thermo_style custom step temp ke pe\nthermo 10\nrun 30\nthermo_style custom step temp press\nrun 30\n";
    std::fs::write(tmp.path().join("in.lj"), deck).unwrap();
    let bin = env!("CARGO_BIN_EXE_dmhs");
    let run = |args: &[&str]| std::process::Command::new(bin).args(args).current_dir(tmp.path()).output().unwrap();
    let o = run(&["run", "in.lj", "-log", "log.lj", "-screen", "none"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // both runs' tables: Temp spans steps 0..60, KinEng only the first run
    let t = dmhs::tools::plot_cmd::read_table(&std::fs::read_to_string(tmp.path().join("log.lj")).unwrap()).unwrap();
    assert_eq!(t.columns, ["Step", "Temp", "KinEng", "PotEng", "Press"]);
    assert_eq!(t.rows.len(), 8);
    assert_eq!((t.rows[0][0], t.rows[7][0]), (0.0, 60.0));
    let o = run(&["plot", "log.lj", "--x", "Step", "--y", "Temp,KinEng", "-o", "thermo.png", "--title", "LJ"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let im = Image::read(&tmp.path().join("thermo.png"));
    assert_eq!((im.w, im.h), (900, 600));
    // the first series is drawn in the chart palette's first colour (0, 114, 178)
    assert!(im.rgb.chunks(3).any(|p| p == [0, 114, 178]));
    let o = run(&["plot", "log.lj", "--y", "temp", "-o", "t.svg"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::read_to_string(tmp.path().join("t.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("Temp") && svg.contains("polyline"));
    // a bad column: a clear error listing the columns, exit code 1
    let o = run(&["plot", "log.lj", "--y", "Volume"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1));
    assert!(err.contains("no column `Volume`; the columns are: Step, Temp, KinEng, PotEng, Press"), "{err}");
    assert!(!tmp.path().join("log.png").exists());
}

#[test]
fn wall_planes_of_a_fix_are_drawn() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = "units lj\ndimension 2\nboundary f f p\nregion box block 0 10 0 5 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 single 5 2.5 0\nmass 1 1\n\
fix w all wall/reflect xlo 2.0 yhi 4.0 units box\n\
dump 1 all image 1 w.*.png type type size 400 200 box no 0.0 fix w const 0.02 0\ndump_modify 1 fcolor w cyan\nrun 0\n";
    run_in(tmp.path(), deck).unwrap();
    let im = Image::read(&tmp.path().join("w.0.png"));
    let cyan = [0, 255, 255];
    // the plane x = 2 is a vertical line, y = 4 a horizontal one (1 pixel wide: 0.02 * 5 = 0.1)
    let (x, y) = at(2.0, 1.0);
    assert!(im.px(x, y) == cyan || im.px(x - 1, y) == cyan, "{:?}", im.px(x, y));
    let (x, y) = at(7.0, 4.0);
    assert!(im.px(x, y) == cyan || im.px(x, y - 1) == cyan, "{:?}", im.px(x, y));
    let (x, y) = at(3.0, 1.0);
    assert_eq!(im.px(x, y), [0, 0, 0]);
    let err = run_in(tmp.path(), &deck.replace("fix w const", "fix nosuch const")).err().unwrap();
    assert!(err.contains("fix `nosuch` does not exist") && err.contains("in.picture:9:"), "{err}");
}

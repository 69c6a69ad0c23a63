//! A small software renderer for `dump image`: an orthographic camera, depth-buffered shaded
//! spheres and cylinders, and PNG/PPM encoding. Pixels are written directly (no drawing crate):
//! particles are discs shaded as spheres, bonds and box edges are capped cylinders.

use nalgebra::Vector3;

/// An RGB colour with components in 0..=1.
pub type Rgb = [f64; 3];
pub type Vec3 = Vector3<f64>;

/// Orthographic camera: screen axes `right` and `up`, `toward` points from the scene to the viewer.
#[derive(Clone, Debug)]
pub struct Camera {
    pub right: Vec3,
    pub up: Vec3,
    pub toward: Vec3,
    /// World point at the image centre.
    pub center: Vec3,
    /// World length of one pixel.
    pub pixel: f64,
    pub width: usize,
    pub height: usize,
}

fn normalized(a: Vec3) -> Option<Vec3> {
    let n = a.norm();
    if n > 0.0 && n.is_finite() { Some(a / n) } else { None }
}

impl Camera {
    /// LAMMPS' view: `theta` from +z and azimuth `phi` (radians) give the direction toward the
    /// viewer; `up` is projected into the image plane. Errors if `up` is parallel to the view.
    pub fn looking(theta: f64, phi: f64, up: Vec3, center: Vec3, pixel: f64, width: usize, height: usize) -> Result<Camera, String> {
        let toward = Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
        let right = normalized(up.cross(&toward)).ok_or("the image up vector is parallel to the view direction")?;
        let up = normalized(toward.cross(&right)).ok_or("the image up vector is parallel to the view direction")?;
        Ok(Camera { right, up, toward, center, pixel, width, height })
    }

    /// Screen position (pixels from the left, pixels from the top) and depth (larger = farther).
    pub fn project(&self, x: Vec3) -> (f64, f64, f64) {
        let d = x - self.center;
        // LAMMPS' pixel grid: the centre point falls on the centre of pixel (W/2, H/2 - 1)
        // counted from the top-left, so positions match its images pixel for pixel
        let sx = 0.5 * self.width as f64 + 0.5 + self.right.dot(&d) / self.pixel;
        let sy = 0.5 * self.height as f64 - 0.5 - self.up.dot(&d) / self.pixel;
        (sx, sy, -self.toward.dot(&d))
    }
}

/// An image with a depth buffer.
pub struct Canvas {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<Rgb>,
    depth: Vec<f64>,
    /// Strength of specular highlights (LAMMPS' `shiny`; 0 = matte).
    pub shiny: f64,
}

/// Half vector between the viewer and a key light at the upper left, in screen axes.
const HALF: Vec3 = Vec3::new(-0.2142, 0.2142, 0.9530);

/// Colour of a surface with unit normal `n` (screen axes: right, up, toward the viewer): the
/// colour itself facing the viewer, darker toward the silhouette, plus a white highlight of
/// strength `shiny` (0: none).
fn shade(c: Rgb, n: Vec3, shiny: f64) -> Rgb {
    let k = 0.45 + 0.55 * n.z.clamp(0.0, 1.0);
    let s = if shiny > 0.0 { shiny * n.dot(&HALF).max(0.0).powf(16.0 * shiny + 1.0) } else { 0.0 };
    [c[0] * k + s, c[1] * k + s, c[2] * k + s]
}

impl Canvas {
    pub fn new(width: usize, height: usize, background: Rgb) -> Canvas {
        Canvas { width, height, rgb: vec![background; width * height], depth: vec![f64::INFINITY; width * height], shiny: 0.0 }
    }

    fn put(&mut self, ix: usize, iy: usize, depth: f64, c: Rgb) {
        let k = iy * self.width + ix;
        if depth < self.depth[k] {
            self.depth[k] = depth;
            self.rgb[k] = c;
        }
    }

    /// Pixel rows and columns whose centres may lie within `r` pixels of (sx, sy).
    fn span(&self, lo: f64, hi: f64, n: usize) -> std::ops::Range<usize> {
        let a = (lo - 0.5).floor().max(0.0);
        let b = (hi + 0.5).ceil().min(n as f64);
        if !(a < b) {
            return 0..0;
        }
        a as usize..b as usize
    }

    /// A sphere of world radius `radius` at `x`. Spheres smaller than a pixel still cover
    /// the pixel under their centre.
    pub fn sphere(&mut self, cam: &Camera, x: Vec3, radius: f64, c: Rgb) {
        let (sx, sy, z) = cam.project(x);
        let thin = radius / cam.pixel < 1.0;
        let r = (radius / cam.pixel).max(0.5);
        if !(sx.is_finite() && sy.is_finite()) {
            return;
        }
        for iy in self.span(sy - r, sy + r, self.height) {
            let dy = iy as f64 + 0.5 - sy;
            for ix in self.span(sx - r, sx + r, self.width) {
                let dx = ix as f64 + 0.5 - sx;
                let q = (dx * dx + dy * dy) / (r * r);
                if q <= 1.0 {
                    let nz = (1.0 - q).sqrt();
                    // below a pixel wide there is nothing to shade: the plain colour
                    let n = if thin { Vec3::z() } else { Vec3::new(dx / r, -dy / r, nz) };
                    self.put(ix, iy, z - nz * radius, shade(c, n, self.shiny));
                }
            }
        }
    }

    /// A cylinder of world diameter `diam` from `a` to `b` with round caps.
    pub fn cylinder(&mut self, cam: &Camera, a: Vec3, b: Vec3, diam: f64, c: Rgb) {
        let (ax, ay, az) = cam.project(a);
        let (bx, by, bz) = cam.project(b);
        if !(ax.is_finite() && ay.is_finite() && bx.is_finite() && by.is_finite()) {
            return;
        }
        let radius = 0.5 * diam;
        let thin = radius / cam.pixel < 1.0;
        let r = (radius / cam.pixel).max(0.5);
        let (ex, ey) = (bx - ax, by - ay);
        let len2 = ex * ex + ey * ey;
        let rows = self.span(ay.min(by) - r, ay.max(by) + r, self.height);
        let cols = self.span(ax.min(bx) - r, ax.max(bx) + r, self.width);
        for iy in rows {
            let py = iy as f64 + 0.5;
            for ix in cols.clone() {
                let px = ix as f64 + 0.5;
                let t = if len2 > 0.0 { (((px - ax) * ex + (py - ay) * ey) / len2).clamp(0.0, 1.0) } else { 0.0 };
                let (dx, dy) = (px - (ax + t * ex), py - (ay + t * ey));
                let q = (dx * dx + dy * dy) / (r * r);
                if q <= 1.0 {
                    let nz = (1.0 - q).sqrt();
                    let n = if thin { Vec3::z() } else { Vec3::new(dx / r, -dy / r, nz) };
                    self.put(ix, iy, az + t * (bz - az) - nz * radius, shade(c, n, self.shiny));
                }
            }
        }
    }

    /// Average `f`x`f` blocks (full-scene anti-aliasing from an image rendered `f` times larger).
    pub fn downsample(&self, f: usize) -> Canvas {
        let (w, h) = (self.width / f, self.height / f);
        let mut out = Canvas::new(w, h, [0.0; 3]);
        let n = (f * f) as f64;
        for y in 0..h {
            for x in 0..w {
                let mut s = [0.0; 3];
                for dy in 0..f {
                    for dx in 0..f {
                        let p = self.rgb[(y * f + dy) * self.width + x * f + dx];
                        for k in 0..3 {
                            s[k] += p[k];
                        }
                    }
                }
                out.rgb[y * w + x] = [s[0] / n, s[1] / n, s[2] / n];
            }
        }
        out
    }

    /// 8-bit RGB bytes, rows from the top.
    pub fn bytes(&self) -> Vec<u8> {
        self.rgb.iter().flat_map(|c| c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)).collect()
    }

    pub fn pixel(&self, ix: usize, iy: usize) -> [u8; 3] {
        self.rgb[iy * self.width + ix].map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
    }

    pub fn png(&self) -> Result<Vec<u8>, String> {
        let mut out = Vec::new();
        {
            let mut enc = png::Encoder::new(&mut out, self.width as u32, self.height as u32);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            // shaded spheres compress poorly with the default filter; adaptive filtering and
            // the best deflate level make scene pictures 2-3 times smaller
            enc.set_compression(png::Compression::Best);
            enc.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
            let mut w = enc.write_header().map_err(|e| e.to_string())?;
            w.write_image_data(&self.bytes()).map_err(|e| e.to_string())?;
        }
        Ok(out)
    }

    /// Binary PPM (P6), as LAMMPS writes for names that are not .jpg/.png.
    pub fn ppm(&self) -> Vec<u8> {
        let mut out = format!("P6\n{} {}\n255\n", self.width, self.height).into_bytes();
        out.extend(self.bytes());
        out
    }
}

/// Decode an 8-bit RGB or RGBA PNG into (width, height, RGB bytes); for tests and tools.
pub fn decode_png(bytes: &[u8]) -> Result<(usize, usize, Vec<u8>), String> {
    let dec = png::Decoder::new(bytes);
    let mut reader = dec.read_info().map_err(|e| e.to_string())?;
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).map_err(|e| e.to_string())?;
    let (w, h) = (info.width as usize, info.height as usize);
    let rgb = match (info.color_type, info.bit_depth) {
        (png::ColorType::Rgb, png::BitDepth::Eight) => buf[..w * h * 3].to_vec(),
        (png::ColorType::Rgba, png::BitDepth::Eight) => buf[..w * h * 4].chunks(4).flat_map(|p| [p[0], p[1], p[2]]).collect(),
        (c, d) => return Err(format!("unsupported PNG layout {c:?} {d:?}")),
    };
    Ok((w, h, rgb))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam(w: usize, h: usize, pixel: f64) -> Camera {
        Camera::looking(0.0, 0.0, Vec3::y(), Vec3::zeros(), pixel, w, h).unwrap()
    }

    #[test]
    fn camera_axes_for_the_2d_view() {
        let c = cam(100, 50, 0.1);
        // +x to the right, +y up, viewer on +z
        let (sx, sy, z) = c.project(Vec3::new(1.0, 0.5, 2.0));
        assert!((sx - 60.5).abs() < 1e-12 && (sy - 19.5).abs() < 1e-12 && (z + 2.0).abs() < 1e-12);
        assert!(Camera::looking(0.0, 0.0, Vec3::z(), Vec3::zeros(), 1.0, 10, 10).is_err());
    }

    #[test]
    fn sphere_covers_its_disc_and_depth_hides_the_far_one() {
        let c = cam(40, 40, 0.1);
        let mut cv = Canvas::new(40, 40, [0.0; 3]);
        cv.sphere(&c, Vec3::zeros(), 1.0, [1.0, 0.0, 0.0]);
        // behind (z = -5) and drawn later: hidden
        cv.sphere(&c, Vec3::new(0.0, 0.0, -5.0), 1.0, [0.0, 0.0, 1.0]);
        let covered: usize = (0..40).flat_map(|y| (0..40).map(move |x| (x, y))).filter(|&(x, y)| cv.pixel(x, y) != [0, 0, 0]).count();
        // a disc of radius 10 pixels: pi r^2 = 314
        assert!((covered as f64 - 314.16).abs() < 12.0, "{covered}");
        assert_eq!(cv.pixel(20, 19), [255, 0, 0]);
        assert_eq!(cv.pixel(2, 2), [0, 0, 0]);
        // the rim is darker than the centre
        assert!(cv.pixel(29, 20)[0] < 200);
    }

    #[test]
    fn cylinder_and_png_roundtrip() {
        let c = cam(30, 20, 0.1);
        let mut cv = Canvas::new(30, 20, [1.0, 1.0, 1.0]);
        cv.cylinder(&c, Vec3::new(-1.0, 0.0, 0.0), Vec3::x(), 0.2, [0.0, 1.0, 0.0]);
        assert!(cv.pixel(15, 9)[1] == 255 && cv.pixel(15, 9)[0] == 0);
        assert_eq!(cv.pixel(15, 2), [255, 255, 255]);
        let png = cv.png().unwrap();
        let (w, h, rgb) = decode_png(&png).unwrap();
        assert_eq!((w, h), (30, 20));
        assert_eq!(rgb, cv.bytes());
        assert!(cv.ppm().starts_with(b"P6\n30 20\n255\n"));
        let small = cv.downsample(2);
        assert_eq!((small.width, small.height), (15, 10));
    }
}

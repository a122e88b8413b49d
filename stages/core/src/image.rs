//! A small RGB raster for the pictures every stage writes (top views, C-space
//! maps, chart plots) and PNG output.
//!
//! This is deliberately plain: pixels, lines, rectangles, a 5x7 bitmap font for
//! axis labels and colour ramps. 3D rendering lives in the docs stage.

use std::path::Path;

#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    /// Row-major RGB, top row first.
    pub data: Vec<u8>,
}

pub type Rgb = [u8; 3];

/// The most bytes a PNG read back ([`Image::decode_png`]) may decode into:
/// what the png crate itself allows a decoder by default; the C-space
/// picture the docs stage reads back takes about 2 MB.
pub const MAX_DECODED_BYTES: usize = 64 << 20;

impl Image {
    pub fn new(width: u32, height: u32, bg: Rgb) -> Self {
        let mut data = Vec::with_capacity((width * height * 3) as usize);
        for _ in 0..(width * height) {
            data.extend_from_slice(&bg);
        }
        Image { width, height, data }
    }

    #[inline]
    pub fn get(&self, x: u32, y: u32) -> Rgb {
        let i = ((y * self.width + x) * 3) as usize;
        [self.data[i], self.data[i + 1], self.data[i + 2]]
    }

    #[inline]
    pub fn set(&mut self, x: i64, y: i64, c: Rgb) {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            return;
        }
        let i = ((y as u32 * self.width + x as u32) * 3) as usize;
        self.data[i..i + 3].copy_from_slice(&c);
    }

    /// Blends `c` over the pixel with opacity `a` in [0, 1].
    #[inline]
    pub fn blend(&mut self, x: i64, y: i64, c: Rgb, a: f64) {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            return;
        }
        let a = a.clamp(0.0, 1.0);
        let i = ((y as u32 * self.width + x as u32) * 3) as usize;
        for k in 0..3 {
            let v = self.data[i + k] as f64 * (1.0 - a) + c[k] as f64 * a;
            self.data[i + k] = v.round() as u8;
        }
    }

    pub fn fill_rect(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, c: Rgb) {
        for y in y0.max(0)..y1.min(self.height as i64) {
            for x in x0.max(0)..x1.min(self.width as i64) {
                self.set(x, y, c);
            }
        }
    }

    /// The columns and rows of the pixels from `minx` to `maxx` and `miny`
    /// to `maxy` (rounded outwards) that lie in the image: what a shape
    /// drawn there may touch. A shape reaching far beyond the image (a
    /// coordinate of 1e300 from a damaged plan) costs no more than the image.
    fn pixels_within(
        &self,
        minx: f64,
        maxx: f64,
        miny: f64,
        maxy: f64,
    ) -> (std::ops::RangeInclusive<i64>, std::ops::RangeInclusive<i64>) {
        let xs = (minx.floor() as i64).max(0)..=(maxx.ceil() as i64).min(self.width as i64 - 1);
        let ys = (miny.floor() as i64).max(0)..=(maxy.ceil() as i64).min(self.height as i64 - 1);
        (xs, ys)
    }

    /// Anti-aliased line of width `w` pixels (distance-based coverage).
    pub fn line(&mut self, x0: f64, y0: f64, x1: f64, y1: f64, w: f64, c: Rgb) {
        let (minx, maxx) = (x0.min(x1) - w - 1.0, x0.max(x1) + w + 1.0);
        let (miny, maxy) = (y0.min(y1) - w - 1.0, y0.max(y1) + w + 1.0);
        let dx = x1 - x0;
        let dy = y1 - y0;
        let len2 = dx * dx + dy * dy;
        let (xs, ys) = self.pixels_within(minx, maxx, miny, maxy);
        for y in ys {
            for x in xs.clone() {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                let t = if len2 > 0.0 { (((px - x0) * dx + (py - y0) * dy) / len2).clamp(0.0, 1.0) } else { 0.0 };
                let (qx, qy) = (x0 + t * dx, y0 + t * dy);
                let d = ((px - qx).powi(2) + (py - qy).powi(2)).sqrt();
                let cov = (w * 0.5 + 0.5 - d).clamp(0.0, 1.0);
                if cov > 0.0 {
                    self.blend(x, y, c, cov);
                }
            }
        }
    }

    pub fn rect_outline(&mut self, x0: f64, y0: f64, x1: f64, y1: f64, w: f64, c: Rgb) {
        self.line(x0, y0, x1, y0, w, c);
        self.line(x1, y0, x1, y1, w, c);
        self.line(x1, y1, x0, y1, w, c);
        self.line(x0, y1, x0, y0, w, c);
    }

    /// Filled anti-aliased disc.
    pub fn disc(&mut self, cx: f64, cy: f64, r: f64, c: Rgb) {
        let (xs, ys) = self.pixels_within(cx - r - 1.0, cx + r + 1.0, cy - r - 1.0, cy + r + 1.0);
        for y in ys {
            for x in xs.clone() {
                let d = ((x as f64 + 0.5 - cx).powi(2) + (y as f64 + 0.5 - cy).powi(2)).sqrt();
                let cov = (r + 0.5 - d).clamp(0.0, 1.0);
                if cov > 0.0 {
                    self.blend(x, y, c, cov);
                }
            }
        }
    }

    /// Draws `text` with the 5x7 font, top-left at (x, y), each font pixel
    /// `scale` image pixels.
    pub fn text(&mut self, x: i64, y: i64, text: &str, scale: i64, c: Rgb) {
        let mut cx = x;
        for ch in text.chars() {
            let g = glyph(ch);
            for (row, bits) in g.iter().enumerate() {
                for col in 0..5 {
                    if bits & (0x10 >> col) != 0 {
                        self.fill_rect(
                            cx + col * scale,
                            y + row as i64 * scale,
                            cx + (col + 1) * scale,
                            y + (row as i64 + 1) * scale,
                            c,
                        );
                    }
                }
            }
            cx += 6 * scale;
        }
    }

    /// Width in pixels of `text` drawn with [`Image::text`].
    pub fn text_width(text: &str, scale: i64) -> i64 {
        text.chars().count() as i64 * 6 * scale
    }

    pub fn encode_png(&self) -> Result<Vec<u8>, png::EncodingError> {
        let mut out = Vec::new();
        {
            let mut enc = png::Encoder::new(&mut out, self.width, self.height);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            let mut w = enc.write_header()?;
            w.write_image_data(&self.data)?;
        }
        Ok(out)
    }

    pub fn write_png(&self, path: &Path) -> std::io::Result<()> {
        let bytes = self.encode_png().map_err(std::io::Error::other)?;
        crate::artifact::write_atomic(path, &bytes)
    }

    /// A PNG of 8-bit RGB or RGBA samples, as liftplan writes its pictures,
    /// read back (the C-space picture in the docs stage, and tests). A
    /// header that asks for more than [`MAX_DECODED_BYTES`] is refused
    /// before anything is allocated for it.
    pub fn decode_png(bytes: &[u8]) -> Result<Image, String> {
        let dec = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut r = dec.read_info().map_err(|e| e.to_string())?;
        let (width, height) = r.info().size();
        let size = r.output_buffer_size().filter(|&s| s <= MAX_DECODED_BYTES).ok_or_else(|| {
            format!("PNG of {width} x {height} pixels: more than the {MAX_DECODED_BYTES} bytes liftplan reads a picture into")
        })?;
        let (_, depth) = r.output_color_type();
        if depth != png::BitDepth::Eight {
            return Err(format!("PNG of {}-bit samples; liftplan's pictures have 8-bit samples", depth as u8));
        }
        let mut buf = vec![0; size];
        let info = r.next_frame(&mut buf).map_err(|e| e.to_string())?;
        let (w, h) = (info.width, info.height);
        let data = match info.color_type {
            png::ColorType::Rgb => buf[..(w * h * 3) as usize].to_vec(),
            png::ColorType::Rgba => buf[..(w * h * 4) as usize].chunks(4).flat_map(|p| [p[0], p[1], p[2]]).collect(),
            other => return Err(format!("unsupported PNG colour type {other:?}")),
        };
        Ok(Image { width: w, height: h, data })
    }
}

/// A perceptually ordered ramp (blue, cyan, green, yellow, red) for heights and
/// distances; `t` in [0, 1].
pub fn ramp(t: f64) -> Rgb {
    const STOPS: [[f64; 3]; 6] = [
        [48.0, 18.0, 59.0],
        [65.0, 125.0, 230.0],
        [30.0, 200.0, 180.0],
        [140.0, 230.0, 60.0],
        [245.0, 180.0, 40.0],
        [180.0, 30.0, 20.0],
    ];
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let x = t * (STOPS.len() - 1) as f64;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - i as f64;
    let mut c = [0u8; 3];
    for k in 0..3 {
        c[k] = (STOPS[i][k] * (1.0 - f) + STOPS[i + 1][k] * f).round() as u8;
    }
    c
}

/// Distinct colours for categories (scan ids, groups).
pub fn category(i: usize) -> Rgb {
    const P: [Rgb; 10] = [
        [31, 119, 180],
        [255, 127, 14],
        [44, 160, 44],
        [214, 39, 40],
        [148, 103, 189],
        [140, 86, 75],
        [227, 119, 194],
        [127, 127, 127],
        [188, 189, 34],
        [23, 190, 207],
    ];
    P[i % P.len()]
}

fn glyph(c: char) -> [u8; 7] {
    match c.to_ascii_uppercase() {
        '0' => [0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E],
        '1' => [0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E],
        '2' => [0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F],
        '3' => [0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E],
        '4' => [0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02],
        '5' => [0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E],
        '6' => [0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E],
        '7' => [0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08],
        '8' => [0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E],
        '9' => [0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C],
        'A' => [0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11],
        'B' => [0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E],
        'C' => [0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E],
        'D' => [0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C],
        'E' => [0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F],
        'F' => [0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10],
        'G' => [0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F],
        'H' => [0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11],
        'I' => [0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E],
        'J' => [0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C],
        'K' => [0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11],
        'L' => [0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F],
        'M' => [0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11],
        'N' => [0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11],
        'O' => [0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E],
        'P' => [0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10],
        'Q' => [0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D],
        'R' => [0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11],
        'S' => [0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E],
        'T' => [0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04],
        'U' => [0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E],
        'V' => [0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04],
        'W' => [0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A],
        'X' => [0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11],
        'Y' => [0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04],
        'Z' => [0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F],
        '.' => [0, 0, 0, 0, 0, 0x0C, 0x0C],
        ',' => [0, 0, 0, 0, 0x0C, 0x04, 0x08],
        ':' => [0, 0x0C, 0x0C, 0, 0x0C, 0x0C, 0],
        '-' => [0, 0, 0, 0x1F, 0, 0, 0],
        '+' => [0, 0x04, 0x04, 0x1F, 0x04, 0x04, 0],
        '/' => [0, 0x01, 0x02, 0x04, 0x08, 0x10, 0],
        '(' => [0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02],
        ')' => [0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08],
        '%' => [0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03],
        '=' => [0, 0, 0x1F, 0, 0x1F, 0, 0],
        '_' => [0, 0, 0, 0, 0, 0, 0x1F],
        '°' => [0x0C, 0x12, 0x12, 0x0C, 0, 0, 0],
        '>' => [0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08],
        '<' => [0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02],
        '#' => [0x0A, 0x0A, 0x1F, 0x0A, 0x1F, 0x0A, 0x0A],
        '\'' => [0x04, 0x04, 0x08, 0, 0, 0, 0],
        ' ' => [0; 7],
        _ => [0x1F, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1F],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_roundtrip_and_drawing() {
        let mut im = Image::new(40, 20, [255, 255, 255]);
        im.line(0.0, 10.0, 40.0, 10.0, 2.0, [0, 0, 0]);
        im.text(1, 1, "A1", 1, [255, 0, 0]);
        assert_eq!(im.get(20, 10), [0, 0, 0]);
        assert_eq!(im.get(20, 2), [255, 255, 255]);
        assert_eq!(im.get(1, 2), [255, 0, 0]);
        let back = Image::decode_png(&im.encode_png().unwrap()).unwrap();
        assert_eq!(back, im);
    }

    /// The CRC-32 of PNG chunks (ISO 3309), bit by bit.
    fn crc32(bytes: &[u8]) -> u32 {
        let mut c = !0u32;
        for &b in bytes {
            c ^= u32::from(b);
            for _ in 0..8 {
                c = if c & 1 != 0 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 };
            }
        }
        !c
    }

    /// A header asking for a picture far larger than any liftplan draws is
    /// refused before a buffer is made for it; samples of other than 8 bits
    /// are refused, not read as garbage.
    #[test]
    fn a_png_too_large_or_not_of_8_bit_samples_is_refused() {
        let mut png = Image::new(1, 1, [1, 2, 3]).encode_png().unwrap();
        // The IHDR chunk's width and height (after the signature, the
        // chunk's length and type), and its CRC over type and data.
        png[16..20].copy_from_slice(&60_000u32.to_be_bytes());
        png[20..24].copy_from_slice(&60_000u32.to_be_bytes());
        let crc = crc32(&png[12..29]);
        png[29..33].copy_from_slice(&crc.to_be_bytes());
        let e = Image::decode_png(&png).unwrap_err();
        assert!(e.starts_with("PNG of 60000 x 60000 pixels: more than the 67108864 bytes"), "{e}");
        let mut deep = Vec::new();
        {
            let mut enc = png::Encoder::new(&mut deep, 2, 2);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Sixteen);
            enc.write_header().unwrap().write_image_data(&[7; 24]).unwrap();
        }
        assert_eq!(
            Image::decode_png(&deep).unwrap_err(),
            "PNG of 16-bit samples; liftplan's pictures have 8-bit samples"
        );
    }

    /// Shapes reaching far beyond the picture draw what lies in it, in no
    /// more time than the picture takes (over their whole extent, the line
    /// below took 1.4 billion pixels' work and the disc 4e24).
    #[test]
    fn shapes_far_beyond_the_picture_draw_only_what_lies_in_it() {
        let white = Image::new(30, 20, [255, 255, 255]);
        let mut line = white.clone();
        line.line(-1e8, 10.0, 1e8, 10.0, 3.0, [0, 0, 0]);
        // The same by hand: 0.5 coverage of rows 8 and 11, full of 9 and 10.
        let mut want = white.clone();
        for (y, cov) in [(8, 0.5), (9, 1.0), (10, 1.0), (11, 0.5)] {
            for x in 0..30 {
                want.blend(x, y, [0, 0, 0], cov);
            }
        }
        assert_eq!(line, want);
        let mut disc = white.clone();
        disc.disc(15.0, 10.0, 1e12, [255, 0, 0]);
        assert_eq!(disc, Image::new(30, 20, [255, 0, 0]));
        // These end at once and draw nothing: the disc lies wholly outside,
        // one line starts at NaN, and the other's squared length overflows
        // (as it did before its pixels were bounded).
        let mut none = white.clone();
        none.line(-1e300, 10.0, 1e300, 10.0, 3.0, [0, 0, 0]);
        none.line(5.0, f64::NAN, 5.0, 1e18, 1.0, [0, 0, 255]);
        none.disc(1e300, -1e300, 4.0, [0, 255, 0]);
        assert_eq!(none, white);
    }

    #[test]
    fn ramp_ends() {
        assert_eq!(ramp(0.0), [48, 18, 59]);
        assert_eq!(ramp(1.0), [180, 30, 20]);
        assert_eq!(ramp(f64::NAN), ramp(0.0));
    }
}

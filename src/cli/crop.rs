//! `raylab render --crop x0,y0,x1,y1`: a rectangle of the image rendered alone, its
//! pixels bit for bit the whole image's (pbrt's `--pixelbounds`).

use anyhow::{Result, bail};
use raylab::params::Params;
use raylab::render::Crop;

/// The rectangle's corners, x0,y0,x1,y1: from pixel (x0, y0) up to, not including,
/// (x1, y1).
pub fn parse_crop(s: &str) -> Result<[u32; 4], String> {
    let corners: Vec<u32> = s
        .split(',')
        .map(|v| v.trim().parse::<u32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("`{s}`: four whole numbers x0,y0,x1,y1"))?;
    <[u32; 4]>::try_from(corners).map_err(|_| format!("`{s}`: four whole numbers x0,y0,x1,y1"))
}

/// Where `[x0, y0, x1, y1]` lies in a `width` × `height` image rendered with `params`: one
/// line (exit status 2) if it is not a rectangle inside the image, or if adaptive
/// sampling, which decides by the image it is given, would make the crop's pixels differ.
pub fn check(
    [x0, y0, x1, y1]: [u32; 4],
    (width, height): (u32, u32),
    params: &Params,
) -> Result<Crop> {
    if !(x0 < x1 && y0 < y1 && x1 <= width && y1 <= height) {
        bail!(
            "--crop {x0},{y0},{x1},{y1}: not a rectangle inside the {width}x{height} image \
             (x0 < x1 <= {width}, y0 < y1 <= {height})"
        );
    }
    if params.noise_target.is_some() {
        bail!(
            "--crop: adaptive sampling decides by the whole image, so a crop's pixels would \
             differ from it; add --set noise_target=off"
        );
    }
    Ok(Crop {
        size: (width, height),
        origin: (x0, y0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_crop_is_four_numbers_inside_the_image() {
        assert_eq!(parse_crop("1,2,30,40"), Ok([1, 2, 30, 40]));
        assert!(parse_crop("1,2,30").is_err());
        assert!(parse_crop("1,2,30,x").is_err());
        let p = Params::default();
        assert!(check([0, 0, 64, 36], (64, 36), &p).is_ok());
        assert!(check([0, 0, 65, 36], (64, 36), &p).is_err());
        assert!(check([5, 0, 5, 36], (64, 36), &p).is_err());
        let adaptive = Params {
            noise_target: Some(1.5),
            ..Params::default()
        };
        assert!(check([0, 0, 8, 8], (64, 36), &adaptive).is_err());
    }
}

//! The charge's toe and shoulder from particle positions: each particle's angle about the
//! drum's axis, measured from the bottom (the direction of gravity across the axis), positive
//! toward the side the shell rises on. Among the particles next to the shell (within two
//! largest diameters of the outermost particle's reach), the shoulder is the 95th percentile of
//! that angle (where the charge leaves the shell on the rising side) and the toe the 5th (where
//! it meets the shell again); the percentiles, not the extremes, so that one ball in flight past
//! the shell does not move them.

use crate::codes::liggghts::mill::RotatingMesh;

/// `(line, reason)` of a file that cannot be read.
pub(super) type ReadFault = (usize, String);

/// One frame of the positions dump.
pub(super) struct Positions {
    /// Its step.
    pub step: f64,
    /// Per particle, its id.
    pub ids: Vec<u64>,
    /// Per particle (as `ids`), its position (m) and radius (m).
    pub particles: Vec<[f64; 4]>,
}

/// Read a `dump custom … id x y z radius` file.
pub(super) fn read_positions(text: &str) -> Result<Vec<Positions>, ReadFault> {
    let lines: Vec<&str> = text.lines().collect();
    let mut frames = Vec::new();
    let mut k = 0;
    while k < lines.len() {
        if lines[k] != "ITEM: TIMESTEP" {
            return Err((k + 1, format!("`{}`: expected ITEM: TIMESTEP", lines[k])));
        }
        let number = |j: usize| {
            lines
                .get(j)
                .and_then(|l| l.trim().parse::<f64>().ok())
                .ok_or((j + 1, "a frame cut short".to_string()))
        };
        let step = number(k + 1)?;
        let n = number(k + 3)?;
        // A count of atoms, written as a whole number.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = n as usize;
        let first = k + 9;
        let mut rows = Vec::with_capacity(n);
        let mut ids = Vec::with_capacity(n);
        for j in first..first + n {
            let words: Vec<f64> = lines
                .get(j)
                .ok_or((j + 1, "a frame cut short".to_string()))?
                .split_whitespace()
                .map(str::parse)
                .collect::<Result<_, _>>()
                .map_err(|e| (j + 1, format!("{e}")))?;
            if words.len() != 5 {
                return Err((
                    j + 1,
                    format!("{} columns, expected id x y z radius", words.len()),
                ));
            }
            // LIGGGHTS writes the id as a whole number.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            ids.push(words[0] as u64);
            rows.push([words[1], words[2], words[3], words[4]]);
        }
        frames.push(Positions {
            step,
            ids,
            particles: rows,
        });
        k = first + n;
    }
    Ok(frames)
}

/// The dot product of two 3-vectors.
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The cross product of two 3-vectors.
pub(super) fn cross(a: &[f64], b: &[f64]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The `q`-quantile of sorted `values` (nearest rank).
fn quantile(sorted: &[f64], q: f64) -> f64 {
    let rank = (q * (sorted.len() - 1) as f64).round();
    // A rank within the slice.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let rank = rank as usize;
    sorted[rank]
}

/// The power the drive supplies to hold the charge's weight off the bottom, W, from one frame:
/// turning steadily, the drum's torque on the charge balances, in the mean, the torque of the
/// charge's weight about the axis, so the drive supplies `−ω (Σ mᵢ (rᵢ − o) × g)·a`. A route
/// to the power draw from positions and masses alone, apart from the forces on the mesh; it
/// leaves out the torque of anything that does not turn with the drum, and the changes of the
/// charge's angular momentum, which average out over a steady rotation.
pub(super) fn weight_power(
    drum: &RotatingMesh,
    gravity: [f64; 3],
    charge: &[(f64, [f64; 3])],
) -> f64 {
    let torque = charge.iter().fold([0.0; 3], |sum, (mass, position)| {
        let arm = [
            position[0] - drum.origin[0],
            position[1] - drum.origin[1],
            position[2] - drum.origin[2],
        ];
        let t = cross(&arm, &gravity);
        [
            sum[0] + mass * t[0],
            sum[1] + mass * t[1],
            sum[2] + mass * t[2],
        ]
    });
    -dot(&torque, &drum.axis) * drum.angular_velocity
}

/// Each particle's place in the drum's cross-section, m: across (toward the rising side) and
/// up (against gravity), from the axis; `None` where gravity runs along the axis.
pub(super) fn section(
    drum: &RotatingMesh,
    gravity: [f64; 3],
    particles: &[[f64; 4]],
) -> Option<Vec<[f64; 2]>> {
    let a = drum.axis;
    let along = dot(&gravity, &a);
    let down = [
        gravity[0] - along * a[0],
        gravity[1] - along * a[1],
        gravity[2] - along * a[2],
    ];
    let size = dot(&down, &down).sqrt();
    if size <= 1e-9 * gravity.iter().map(|g| g.abs()).fold(0.0, f64::max) {
        return None;
    }
    let down = down.map(|x| x / size);
    // The shell's bottom moves along ω a × down: that side rises.
    let rising = cross(&a, &down).map(|x| x * drum.angular_velocity.signum());
    Some(
        particles
            .iter()
            .map(|p| {
                let r = [
                    p[0] - drum.origin[0],
                    p[1] - drum.origin[1],
                    p[2] - drum.origin[2],
                ];
                [dot(&r, &rising), -dot(&r, &down)]
            })
            .collect(),
    )
}

/// Toe and shoulder of one frame, degrees from the bottom (toe negative, shoulder positive on
/// the rising side), or `None` when the frame holds no particle or gravity runs along the axis.
pub(super) fn toe_and_shoulder(
    drum: &RotatingMesh,
    gravity: [f64; 3],
    particles: &[[f64; 4]],
) -> Option<(f64, f64)> {
    if particles.is_empty() {
        return None;
    }
    let polar: Vec<(f64, f64)> = section(drum, gravity, particles)?
        .iter()
        .zip(particles)
        .map(|(&[y, up], p)| {
            let x = -up;
            ((x * x + y * y).sqrt() + p[3], y.atan2(x).to_degrees())
        })
        .collect();
    let reach = polar.iter().map(|p| p.0).fold(0.0, f64::max);
    let largest = particles.iter().map(|p| p[3]).fold(0.0, f64::max);
    let mut near: Vec<f64> = polar
        .iter()
        .filter(|p| p.0 >= reach - 4.0 * largest)
        .map(|p| p.1)
        .collect();
    near.sort_by(f64::total_cmp);
    Some((quantile(&near, 0.05), quantile(&near, 0.95)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codes::deck::SourceLine;

    /// A drum about +y turning at +9 rad/s, gravity −z: the bottom moves toward −x (ω ŷ × −ẑ),
    /// so the rising side is −x. A charge of balls on the shell from 30° before the bottom to
    /// 60° past it on the rising side, and balls inside it: toe −30°, shoulder 60°.
    #[test]
    fn toe_and_shoulder_of_a_charge_on_the_shell() {
        let drum = RotatingMesh {
            mesh: "drum".into(),
            origin: [0.0; 3],
            axis: [0.0, 1.0, 0.0],
            angular_velocity: 9.0,
            from: SourceLine {
                file: "in.mill".into(),
                line: 1,
            },
        };
        let (radius, shell) = (0.005, 0.07);
        let mut particles = Vec::new();
        for k in 0..=90 {
            let angle = f64::from(k - 30).to_radians();
            let r = shell - radius;
            // Rising side is −x: the angle runs from −z toward −x.
            particles.push([-r * angle.sin(), 0.0, -r * angle.cos(), radius]);
            particles.push([-0.5 * r * angle.sin(), 0.0, -0.5 * r * angle.cos(), radius]);
        }
        let (toe, shoulder) = toe_and_shoulder(&drum, [0.0, 0.0, -1.0], &particles).unwrap();
        assert!((toe - -25.0).abs() < 1.01, "toe {toe}");
        assert!((shoulder - 55.0).abs() < 1.01, "shoulder {shoulder}");
        // Turning the other way, the sides swap.
        let back = RotatingMesh {
            angular_velocity: -9.0,
            ..drum
        };
        let (toe, shoulder) = toe_and_shoulder(&back, [0.0, 0.0, -1.0], &particles).unwrap();
        assert!((toe - -55.0).abs() < 1.01 && (shoulder - 25.0).abs() < 1.01);
        // Gravity along the axis has no bottom.
        assert_eq!(toe_and_shoulder(&back, [0.0, 1.0, 0.0], &particles), None);
    }

    /// A drum about +y at +9 rad/s, gravity −9.81 ẑ: its rising side is −x. A 2 kg charge held
    /// 0.03 m toward the rising side needs ω m g d = 9 × 2 × 9.81 × 0.03 W; toward the falling
    /// side the weight would drive the drum (negative power); along the axis or straight below
    /// it, nothing.
    #[test]
    fn weight_power_is_the_torque_of_the_lifted_charge_times_the_speed() {
        let drum = RotatingMesh {
            mesh: "drum".into(),
            origin: [0.0, 0.5, 0.0],
            axis: [0.0, 1.0, 0.0],
            angular_velocity: 9.0,
            from: SourceLine {
                file: "in.mill".into(),
                line: 1,
            },
        };
        let g = [0.0, 0.0, -9.81];
        let lifted = weight_power(
            &drum,
            g,
            &[(1.5, [-0.03, 0.2, -0.05]), (0.5, [-0.03, 0.9, 0.01])],
        );
        approx::assert_relative_eq!(lifted, 9.0 * 2.0 * 9.81 * 0.03, max_relative = 1e-14);
        let falling = weight_power(&drum, g, &[(2.0, [0.03, 0.0, -0.05])]);
        approx::assert_relative_eq!(falling, -lifted, max_relative = 1e-14);
        assert!(weight_power(&drum, g, &[(2.0, [0.0, 3.0, -0.06])]).abs() < 1e-15);
    }
}

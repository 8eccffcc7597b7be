//! Built-in scenes: small rigid-body configurations assembled in code (no files) into
//! FC(W, q, mu), the way a Moreau-Jean time stepper would at one step.
//!
//! Every body has generalized velocity `v = (linear, angular)` (world frame, angular about the
//! center of mass) and mass matrix `M = diag(m I, I_body)`. A contact `c` between body `A` and
//! body `B` (or the fixed ground/walls) has a point `p`, a frame `(n, t1, t2)` with `n` pointing
//! from `B` into `A`, and a Jacobian `G_c` such that its local relative velocity is
//!
//! `u_c = G_cA v_A - G_cB v_B`, with `G_cK = [d^T  ((p - x_K) x d)^T]` for each frame direction `d`.
//!
//! One time step of length `dt` under gravity gives `v+ = v_free + M^-1 G^T r` (r are impulses),
//! `v_free = v + dt M^-1 f_ext`, hence `u = W r + q` with `W = G M^-1 G^T` (symmetric positive
//! semi-definite, rank-deficient as soon as there are more contact rows than degrees of freedom)
//! and `q = G v_free`. The block `W_cd` is non-zero exactly when contacts `c` and `d` share a body.
//!
//! One scene ([`gyro`](default_scenes)) replaces `M` by the iteration matrix `M + dt C(omega)`
//! of the linearised gyroscopic term `omega x I omega`, `C = [omega]_x I - [I omega]_x`, which makes
//! `W` non-symmetric (relative asymmetry around 1e-4), as the W of real simulators are.

pub mod sequences;

use crate::error::Fc3dError;
use crate::problem::FrictionProblem;

mod boxes;
mod builtin;
mod fcc;
mod global_form;
mod granular;
pub mod towers;
mod world;
pub use boxes::box_piles;
pub use builtin::{default_scenes, Scene};
pub use fcc::fcc_piles;
pub use granular::{sphere_piles, PileSpec};
pub use towers::{box_towers, TowerMotion, TowerSpec};

/// The bodies a generated scene is made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PileShape {
    /// Square pyramids of spheres ([`sphere_piles`], the default).
    #[default]
    Spheres,
    /// Stepped pyramids of boxes, 4 contact points per face contact
    /// ([`box_piles`]).
    Boxes,
    /// Boxes of spheres in a regular face-centred cubic lattice ([`fcc_piles`]).
    Fcc,
}

impl PileShape {
    /// The shape's name, as [`PileShape::from_name`] reads it.
    pub fn label(&self) -> &'static str {
        match self {
            PileShape::Spheres => "spheres",
            PileShape::Boxes => "boxes",
            PileShape::Fcc => "fcc",
        }
    }

    /// The shape named `spheres`, `boxes` or `fcc`.
    pub fn from_name(name: &str) -> Result<PileShape, Fc3dError> {
        match name.trim() {
            "spheres" => Ok(PileShape::Spheres),
            "boxes" => Ok(PileShape::Boxes),
            "fcc" => Ok(PileShape::Fcc),
            other => Err(Fc3dError::InvalidOption(format!(
                "unknown shape '{other}' (spheres, boxes, fcc)"
            ))),
        }
    }
}

/// A generated scene: the piles and what they are made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GeneratedScene {
    pub pile: PileSpec,
    pub shape: PileShape,
}

impl GeneratedScene {
    /// Parses `contacts=N,piles=P,seed=S,shape=spheres|boxes|fcc` (any order; `piles` defaults to 1,
    /// `seed` to 1, `shape` to spheres).
    pub fn parse(text: &str) -> Result<GeneratedScene, Fc3dError> {
        parse_spec(text, true)
    }

    /// A short name for tables and files: `piles-c100000-p4-s1` (spheres),
    /// `boxes-c100000-p4-s1`, `fcc-c100000-p4-s1`.
    pub fn name(&self) -> String {
        let prefix = match self.shape {
            PileShape::Spheres => return self.pile.name(),
            PileShape::Boxes => "boxes",
            PileShape::Fcc => "fcc",
        };
        format!(
            "{prefix}-c{}-p{}-s{}",
            self.pile.contacts, self.pile.piles, self.pile.seed
        )
    }

    /// The height of each pile in layers of bodies (a pile is built bottom-up until its share
    /// of the contacts is spent, so its top layers may be missing from the full pyramid).
    pub fn pile_layers(&self) -> Vec<usize> {
        let layers = |contacts: usize| match self.shape {
            PileShape::Spheres => granular::pile_shape(contacts, granular::layer_contacts).1,
            PileShape::Boxes => granular::pile_shape(contacts, boxes::layer_contacts).1,
            PileShape::Fcc => fcc::box_shape(contacts).1,
        };
        (0..self.pile.piles)
            .map(|p| layers(self.pile.pile_contacts(p)))
            .collect()
    }

    /// Generates the scene (sparse-block W).
    pub fn generate(&self) -> Result<FrictionProblem<'static>, Fc3dError> {
        match self.shape {
            PileShape::Spheres => sphere_piles(&self.pile),
            PileShape::Boxes => box_piles(&self.pile),
            PileShape::Fcc => fcc_piles(&self.pile),
        }
    }
}

/// The keys of a scene spec; `shape` only where a shape can be chosen.
fn parse_spec(text: &str, with_shape: bool) -> Result<GeneratedScene, Fc3dError> {
    let mut pile = PileSpec {
        contacts: 0,
        piles: 1,
        seed: 1,
    };
    let mut shape = PileShape::Spheres;
    let bad = |why: String| Fc3dError::InvalidOption(format!("scene spec '{text}': {why}"));
    for part in text.split(',').filter(|p| !p.trim().is_empty()) {
        let (key, value) = part
            .split_once('=')
            .ok_or_else(|| bad(format!("'{part}' is not key=value")))?;
        if with_shape && key.trim() == "shape" {
            shape = PileShape::from_name(value).map_err(|e| bad(e.to_string()))?;
            continue;
        }
        let number: u64 = value
            .trim()
            .replace('_', "")
            .parse()
            .map_err(|_| bad(format!("'{value}' is not a non-negative integer")))?;
        match key.trim() {
            "contacts" => pile.contacts = number as usize,
            "piles" => pile.piles = number as usize,
            "seed" => pile.seed = number,
            other => {
                let keys = if with_shape {
                    "contacts, piles, seed, shape"
                } else {
                    "contacts, piles, seed"
                };
                return Err(bad(format!("unknown key '{other}' ({keys})")));
            }
        }
    }
    pile.check()?;
    Ok(GeneratedScene { pile, shape })
}

/// Time step of every scene (s).
pub const DT: f64 = 0.01;
/// Gravity (m/s^2), along -z.
pub const GRAVITY: f64 = 9.81;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_specs_parse_with_their_shape() {
        let s = GeneratedScene::parse("contacts=100,shape=boxes,piles=2").unwrap();
        assert_eq!(
            s.pile,
            PileSpec {
                contacts: 100,
                piles: 2,
                seed: 1
            }
        );
        assert_eq!(s.shape, PileShape::Boxes);
        assert_eq!(s.name(), "boxes-c100-p2-s1");
        let d = GeneratedScene::parse("contacts=100").unwrap();
        assert_eq!(d.shape, PileShape::Spheres);
        assert_eq!(d.name(), "piles-c100-p1-s1");
        assert!(GeneratedScene::parse("contacts=100,shape=cones").is_err());
        // A plain pile spec has no shape.
        assert!(PileSpec::parse("contacts=100,shape=boxes").is_err());
        assert_eq!(
            granular::tests::bits(
                &GeneratedScene::parse("contacts=50,shape=boxes")
                    .unwrap()
                    .generate()
                    .unwrap()
            ),
            granular::tests::bits(
                &box_piles(&PileSpec {
                    contacts: 50,
                    piles: 1,
                    seed: 1
                })
                .unwrap()
            )
        );
    }

    #[test]
    fn pile_layers_count_the_layers_built() {
        // A full sphere pyramid of base 2: 4 on the ground + 4 lateral, then 1 sphere on 4.
        let full = GeneratedScene::parse("contacts=12").unwrap();
        assert_eq!(full.pile_layers(), vec![2]);
        // One contact more needs base 3, whose first layer alone holds 9 + 12 = 21.
        let one_layer = GeneratedScene::parse("contacts=13").unwrap();
        assert_eq!(one_layer.pile_layers(), vec![1]);
        // Boxes of base 3: 36 on the ground, then 64 and 16 above.
        let boxes = GeneratedScene::parse("contacts=116,shape=boxes,piles=2").unwrap();
        assert_eq!(boxes.pile_layers(), vec![2, 2]);
        let boxes = GeneratedScene::parse("contacts=116,shape=boxes").unwrap();
        assert_eq!(boxes.pile_layers(), vec![3]);
    }
}

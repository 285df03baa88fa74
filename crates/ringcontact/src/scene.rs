//! A scene: punch + material + load + the accuracy wanted. Read from TOML, validated.
//!
//! ```toml
//! [punch]
//! shape = "power"           # a built-in shape (`verify references` lists them)
//! rim_radius = 1.0          # a, length unit of your choice (a ring's radius where it has no rim)
//! hole_depth = 0.1          # h, the depth of a recessed shape's hole (its gap at the axis)
//! exponent = 2.5            # a shape's own parameter, where it takes one: exponent (n of
//! #                         # h (1 - (r/a)^n)), tube_radius (rho of a ring's section),
//! #                         # profile ((r/a, g/h) points, relative to the scene file),
//! #                         # inner_radius (b of a fixed annulus, 0 <= b < a)
//!
//! [material]
//! effective_modulus = 1.0   # E* = E/(1 - nu²); or give youngs_modulus and poisson_ratio
//!
//! [load]                    # exactly one of:
//! depth = 0.2               # d, indentation of the rim (positive into the solid)
//! # force = 0.5             # F, positive in compression
//! # contact_ratio = 0.5     # eps = b/a prescribed (concave punches): d and F are computed
//!
//! [accuracy]
//! tolerance = 1e-9          # relative error wanted (default: the method's, 1e-9 ring BEM, 1e-3 FEM)
//! ```
//!
//! Every field is checked; a broken rule is reported with the field's name and the rule.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::punch::{Contact, Punch, PunchKind, PunchName};

mod keywords;
pub use keywords::{in_keywords, keyword_names};

/// Default tolerance of the ring BEM (each method has its own default; see `methods`).
pub const DEFAULT_TOLERANCE: f64 = 1e-9;

/// Linear elastic, isotropic half-space; the punch is rigid.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// `E* = E / (1 - nu²)`, stress units.
    pub effective_modulus: f64,
    /// Young's modulus `E`, if given.
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio `nu`, if given.
    pub poisson_ratio: Option<f64>,
}

/// What is prescribed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Load {
    /// Indentation depth `d` of the rim.
    Depth(f64),
    /// Normal force `F` (compression positive).
    Force(f64),
    /// Contact ratio `eps = b/a` of a concave punch; depth and force follow.
    ContactRatio(f64),
}

/// A validated scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Scene {
    pub punch: Punch,
    pub material: Material,
    pub load: Load,
    /// Relative error wanted in the dimensionless results; `None`: the method's default.
    pub tolerance: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawPunch {
    shape: Option<PunchName>,
    exponent: Option<f64>,
    rim_radius: Option<f64>,
    inner_radius: Option<f64>,
    hole_depth: Option<f64>,
    tube_radius: Option<f64>,
    profile: Option<std::path::PathBuf>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    effective_modulus: Option<f64>,
    youngs_modulus: Option<f64>,
    poisson_ratio: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawLoad {
    depth: Option<f64>,
    force: Option<f64>,
    contact_ratio: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawAccuracy {
    tolerance: Option<f64>,
}

/// The scene as written in TOML (all fields optional so that the command line can fill gaps).
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    #[serde(default)]
    punch: RawPunch,
    #[serde(default)]
    material: RawMaterial,
    #[serde(default)]
    load: RawLoad,
    #[serde(default)]
    accuracy: RawAccuracy,
    /// `b/a` given instead of `b` (command line `--eps`); resolved against the rim radius.
    #[serde(skip)]
    inner_ratio: Option<f64>,
    /// The directory a relative `punch.profile` of a scene file is read from.
    #[serde(skip)]
    profile_base: Option<std::path::PathBuf>,
    /// A profile that is neither built in nor a table file: a user's own [`Profile`] type.
    ///
    /// [`Profile`]: crate::punch::Profile
    #[serde(skip)]
    own_profile: Option<PunchKind>,
}

impl SceneSpec {
    /// Parse a TOML scene; unknown keys and wrong types are errors naming the key.
    pub fn from_toml(text: &str, origin: &str) -> Result<Self> {
        toml::from_str(text).map_err(|e| {
            // Line and column of the offending text (1-based), from the error's byte span.
            let place = e.span().map(|span| {
                let before = &text.as_bytes()[..span.start.min(text.len())];
                let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
                let column = before.iter().rev().take_while(|&&b| b != b'\n').count() + 1;
                let snippet: String = text
                    .lines()
                    .nth(line - 1)
                    .unwrap_or("")
                    .chars()
                    .take(80)
                    .collect();
                format!("line {line}, column {column} (`{}`): ", snippet.trim())
            });
            Error::SceneFile {
                path: origin.to_string(),
                message: format!("{}{}", place.unwrap_or_default(), e.message().trim()),
            }
        })
    }

    /// Read and parse a TOML scene file.
    pub fn from_file(path: &std::path::Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::SceneFile {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        let mut spec = Self::from_toml(&text, &path.display().to_string())?;
        if let Some(profile) = &spec.punch.profile {
            if profile.is_relative() {
                spec.profile_base = path.parent().map(std::path::Path::to_path_buf);
            }
        }
        Ok(spec)
    }

    /// A scene written as a JSON object with the keys of the TOML file (`{"punch": {"shape":
    /// "flat"}, "load": {"depth": 2}}`), as `verify solve --batch` reads it; a relative
    /// `punch.profile` is read from `base` (the batch file's directory). Unknown keys and wrong
    /// types are errors naming the key.
    pub fn from_json_value(
        value: serde_json::Value,
        origin: &str,
        base: Option<&std::path::Path>,
    ) -> Result<Self> {
        keywords::check_types(&value)?;
        let mut spec: Self = serde_json::from_value(value).map_err(|e| Error::SceneFile {
            path: origin.to_string(),
            message: e.to_string(),
        })?;
        if spec.punch.profile.as_ref().is_some_and(|p| p.is_relative()) {
            spec.profile_base = base.map(std::path::Path::to_path_buf);
        }
        Ok(spec)
    }

    /// The tolerance the scene states (`accuracy.tolerance`), if any.
    pub fn stated_tolerance(&self) -> Option<f64> {
        self.accuracy.tolerance
    }

    /// Set the profile file of a punch given by points (read relative to the working
    /// directory).
    pub fn profile(mut self, path: &std::path::Path) -> Self {
        self.punch.profile = Some(path.to_path_buf());
        self.profile_base = None;
        self
    }

    /// Set the punch shape (with its parameters: an exponent, a profile file); a
    /// user's own profile (`PunchKind::new(MyProfile)`) is taken as it is.
    pub fn shape(mut self, kind: PunchKind) -> Self {
        if kind.shape_name().is_none() {
            self.punch.shape = None;
            self.punch.exponent = None;
            self.punch.profile = None;
            self.own_profile = Some(kind);
            return self;
        }
        self.own_profile = None;
        self.punch.shape = kind.shape_name();
        self.punch.exponent = kind.exponent();
        if let Some(file) = kind.record().profile_file {
            self = self.profile(std::path::Path::new(&file));
        }
        self
    }

    /// Set the punch shape by name and its exponent, each only where given (a
    /// scene file's values stay where the command line is silent).
    pub fn shape_named(mut self, name: Option<PunchName>, exponent: Option<f64>) -> Self {
        if let Some(name) = name {
            self.own_profile = None;
            if name != self.punch.shape.unwrap_or(name) {
                // The other shape's parameters do not carry over.
                self.punch.exponent = None;
                self.punch.tube_radius = None;
                self.punch.profile = None;
                if name.contact() == Contact::FreeBand {
                    self.punch.hole_depth = None;
                }
            }
            self.punch.shape = Some(name);
        }
        if exponent.is_some() {
            self.punch.exponent = exponent;
        }
        self
    }

    /// The scene of the flat keywords `object` (`{"punch": "flat", "depth": 2}`): each key is
    /// placed in its section of the scene file and read as the file is
    /// ([`SceneSpec::from_json_value`]); `eps` is `b/a` as `--eps` takes it. Unknown keys, a key
    /// given twice (`punch` and `shape`), and `eps` beside another load are errors naming them.
    pub fn from_keywords(
        object: serde_json::Map<String, serde_json::Value>,
        origin: &str,
        base: Option<&std::path::Path>,
    ) -> Result<Self> {
        keywords::from_keywords(object, origin, base)
    }

    /// Set `b/a` as `--eps` does: the fixed annulus's hole (against the rim radius), or the
    /// prescribed contact ratio of a punch whose contact is found (a rim's free inner edge or
    /// a free band). The flat circular punch has no `b/a`: an error.
    pub fn eps(self, eps: f64) -> Result<Self> {
        keywords::with_eps(self, eps)
    }

    /// The punch shape named so far (file or command line), if any.
    pub fn shape_name(&self) -> Option<PunchName> {
        self.punch.shape
    }

    /// Set a free band's tube radius `ρ` (length units), its depth scale `h = a²/(2ρ)`.
    pub fn tube_radius(mut self, rho: f64) -> Self {
        self.punch.tube_radius = Some(rho);
        self
    }

    /// Set the rim radius `a` (a free band's ring radius), length units.
    pub fn rim_radius(mut self, a: f64) -> Self {
        self.punch.rim_radius = Some(a);
        self
    }

    /// Set the hole depth `h` of a concave punch, length units.
    pub fn hole_depth(mut self, h: f64) -> Self {
        self.punch.hole_depth = Some(h);
        self
    }

    /// Set the effective modulus `E* = E/(1 - ν²)`, stress units.
    pub fn effective_modulus(mut self, modulus: f64) -> Self {
        self.material = RawMaterial {
            effective_modulus: Some(modulus),
            ..Default::default()
        };
        self
    }

    /// Set `b/a` of a fixed annulus (with the rim radius of the scene, default 1).
    pub fn inner_ratio(mut self, eps: f64) -> Self {
        self.punch.inner_radius = None;
        self.inner_ratio = Some(eps);
        self
    }

    /// Set the indentation depth (replaces any other load).
    pub fn depth(mut self, d: f64) -> Self {
        self.load = RawLoad {
            depth: Some(d),
            ..Default::default()
        };
        self
    }

    /// Set the force (replaces any other load).
    pub fn force(mut self, f: f64) -> Self {
        self.load = RawLoad {
            force: Some(f),
            ..Default::default()
        };
        self
    }

    /// Prescribe the contact ratio of a concave punch (replaces any other load).
    pub fn contact_ratio(mut self, eps: f64) -> Self {
        self.load = RawLoad {
            contact_ratio: Some(eps),
            ..Default::default()
        };
        self
    }

    /// Set the tolerance.
    pub fn tolerance(mut self, tol: f64) -> Self {
        self.accuracy.tolerance = Some(tol);
        self
    }
}

/// `value` must be a finite number.
fn finite(field: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(
            field,
            format!(
                "must be a finite number (got {})",
                crate::error::show(value)
            ),
        ))
    }
}

/// `value` must be finite and strictly positive.
fn positive(field: &str, value: f64) -> Result<f64> {
    let v = finite(field, value)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(Error::invalid(
            field,
            format!("must be > 0 (got {})", crate::error::show(v)),
        ))
    }
}

impl SceneSpec {
    /// The punch named (shape, exponent, profile file) or given as a user's own profile.
    fn punch_kind(&self) -> Result<PunchKind> {
        if let Some(kind) = &self.own_profile {
            return Ok(kind.clone());
        }
        let name = self.punch.shape.ok_or_else(|| {
            Error::invalid(
                "punch.shape",
                format!("is required: one of {}", PunchName::names(None, ", ")),
            )
        })?;
        let profile = self
            .punch
            .profile
            .as_ref()
            .map(|p| match &self.profile_base {
                Some(base) => base.join(p),
                None => p.clone(),
            });
        name.with_parameters(self.punch.exponent, profile.as_deref())
            .map_err(|e| match e {
                Error::InvalidScene { field, rule } => {
                    Error::invalid(&format!("punch.{field}"), rule)
                }
                other => other,
            })
    }

    /// Apply defaults (`a = 1`, `E* = 1`, `h = 1`, depth 1 for flat punches; the tolerance is
    /// left to the method when not given)
    /// and check every rule. The error names the field and the rule it breaks.
    pub fn validate(self) -> Result<Scene> {
        let kind = self.punch_kind()?;
        let rim_radius = positive("punch.rim_radius", self.punch.rim_radius.unwrap_or(1.0))?;
        let inner_radius = self.inner_radius(&kind, rim_radius)?;
        let hole_depth = self.hole_depth_of(&kind, rim_radius)?;
        let material = self.material.validate()?;
        let load = self.load.validate(kind.clone())?;
        let tolerance = self.accuracy.tolerance.map(valid_tolerance).transpose()?;
        Ok(Scene {
            punch: Punch {
                kind,
                rim_radius,
                inner_radius,
                hole_depth,
            },
            material,
            load,
            tolerance,
        })
    }

    /// The inner radius `b` of a punch with a fixed hole (`0 <= b < a`, from `inner_radius` or
    /// `b/a`), zero for the others, which take neither.
    fn inner_radius(&self, kind: &PunchKind, rim_radius: f64) -> Result<f64> {
        let fixed_hole = kind.has_fixed_hole();
        let inner_radius = match (fixed_hole, self.punch.inner_radius, self.inner_ratio) {
            (true, Some(_), Some(_)) => {
                return Err(Error::invalid(
                    "punch.inner_radius",
                    "is given twice (as inner_radius and as eps = b/a); give one",
                ))
            }
            (true, Some(b), None) => finite("punch.inner_radius", b)?,
            (true, None, Some(eps)) => finite("eps", eps)? * rim_radius,
            (true, None, None) => {
                return Err(Error::invalid(
                    "punch.inner_radius",
                    format!("is required for shape = {kind} (or give eps = b/a)"),
                ))
            }
            (_, Some(_), _) | (_, _, Some(_)) => {
                return Err(Error::invalid(
                    "punch.inner_radius",
                    format!(
                        "applies only to shape = {}, not {kind} \
                         (for the concave punches the inner radius is found by the solver; \
                         prescribe it with load.contact_ratio)",
                        PunchName::names(Some(Contact::FixedAnnulus), ", ")
                    ),
                ))
            }
            _ => 0.0,
        };
        if fixed_hole && !(0.0..rim_radius).contains(&inner_radius) {
            return Err(Error::invalid(
                "punch.inner_radius",
                format!(
                    "must satisfy 0 <= b < a (got b = {}, a = {}; b >= a leaves no contact, \
                     b < 0 is no radius)",
                    crate::error::show(inner_radius),
                    crate::error::show(rim_radius)
                ),
            ));
        }
        Ok(inner_radius)
    }

    /// The depth scale `h`: the hole depth of a concave punch (default 1), `a²/(2 ρ)` of a free
    /// band from its tube radius `ρ`, zero for the flat punches, which take neither.
    fn hole_depth_of(&self, kind: &PunchKind, rim_radius: f64) -> Result<f64> {
        let free_band = kind.is_free_band();
        Ok(
            match (free_band, self.punch.hole_depth, self.punch.tube_radius) {
                (false, _, Some(_)) => {
                    return Err(Error::invalid(
                        "punch.tube_radius",
                        format!(
                            "applies only to shape = {} (a punch whose contact edges are \
                             both free), not {kind}",
                            PunchName::names(Some(Contact::FreeBand), " or ")
                        ),
                    ))
                }
                (true, Some(_), _) => {
                    return Err(Error::invalid(
                        "punch.hole_depth",
                        format!(
                            "does not apply to the {kind}: its depth scale h = a²/(2 rho) \
                             follows from punch.tube_radius"
                        ),
                    ))
                }
                (true, None, Some(rho)) => {
                    let rho = positive("punch.tube_radius", rho)?;
                    let h = rim_radius * rim_radius / (2.0 * rho);
                    finite("punch.tube_radius", h).and_then(|h| positive("punch.tube_radius", h))?
                }
                (true, None, None) => {
                    return Err(Error::invalid(
                        "punch.tube_radius",
                        format!(
                            "is required for shape = {kind} (--tube-radius RHO): its depth \
                             scale is h = a²/(2 rho)"
                        ),
                    ))
                }
                (_, h, None) if kind.is_concave() => {
                    positive("punch.hole_depth", h.unwrap_or(1.0))?
                }
                (_, Some(_), None) => {
                    return Err(Error::invalid(
                        "punch.hole_depth",
                        format!(
                            "applies only to the concave shapes ({}), not {kind}",
                            PunchName::names(Some(Contact::RimAndFreeInner), ", ")
                        ),
                    ))
                }
                _ => 0.0,
            },
        )
    }
}

/// A relative tolerance: positive and below 1.
fn valid_tolerance(t: f64) -> Result<f64> {
    let t = positive("accuracy.tolerance", t)?;
    if t >= 1.0 {
        return Err(Error::invalid(
            "accuracy.tolerance",
            format!(
                "is a relative error and must be < 1 (got {})",
                crate::error::show(t)
            ),
        ));
    }
    Ok(t)
}

impl RawMaterial {
    fn validate(self) -> Result<Material> {
        match (
            self.effective_modulus,
            self.youngs_modulus,
            self.poisson_ratio,
        ) {
            (Some(_), Some(_), _) | (Some(_), _, Some(_)) => Err(Error::invalid(
                "material",
                "give either effective_modulus, or youngs_modulus with poisson_ratio, not both",
            )),
            (Some(es), None, None) => Ok(Material {
                effective_modulus: positive("material.effective_modulus", es)?,
                youngs_modulus: None,
                poisson_ratio: None,
            }),
            (None, Some(e), Some(nu)) => {
                let e = positive("material.youngs_modulus", e)?;
                let nu = finite("material.poisson_ratio", nu)?;
                if !(nu > -1.0 && nu < 0.5) {
                    return Err(Error::invalid(
                        "material.poisson_ratio",
                        format!(
                            "must lie in the open interval (-1, 0.5) (got {})",
                            crate::error::show(nu)
                        ),
                    ));
                }
                Ok(Material {
                    effective_modulus: e / (1.0 - nu * nu),
                    youngs_modulus: Some(e),
                    poisson_ratio: Some(nu),
                })
            }
            (None, Some(_), None) => Err(Error::invalid(
                "material.poisson_ratio",
                "is required with youngs_modulus (E* = E/(1 - nu²))",
            )),
            (None, None, Some(_)) => Err(Error::invalid(
                "material.youngs_modulus",
                "is required with poisson_ratio (E* = E/(1 - nu²))",
            )),
            (None, None, None) => Ok(Material {
                effective_modulus: 1.0,
                youngs_modulus: None,
                poisson_ratio: None,
            }),
        }
    }
}

impl RawLoad {
    fn validate(self, kind: PunchKind) -> Result<Load> {
        let given = [
            self.depth.is_some(),
            self.force.is_some(),
            self.contact_ratio.is_some(),
        ]
        .iter()
        .filter(|&&g| g)
        .count();
        if given > 1 {
            return Err(Error::invalid(
                "load",
                "has more than one of depth, force, contact_ratio: give exactly one",
            ));
        }
        if let Some(d) = self.depth {
            return Ok(Load::Depth(positive("load.depth", d)?));
        }
        if let Some(f) = self.force {
            return Ok(Load::Force(positive("load.force", f)?));
        }
        if let Some(eps) = self.contact_ratio {
            if !kind.is_concave() {
                return Err(Error::invalid(
                    "load.contact_ratio",
                    format!(
                        "applies only to the punches whose contact edges are found ({}; for \
                         {kind} the contact is fixed by the geometry; use inner_radius or eps \
                         = b/a)",
                        PunchName::names(Some(Contact::RimAndFreeInner), ", ")
                            + ", "
                            + &PunchName::names(Some(Contact::FreeBand), ", ")
                    ),
                ));
            }
            let eps = finite("load.contact_ratio", eps)?;
            if !(eps > 0.0 && eps < 1.0) {
                return Err(Error::invalid(
                    "load.contact_ratio",
                    format!("must satisfy 0 < b/a < 1 (got {})", crate::error::show(eps)),
                ));
            }
            return Ok(Load::ContactRatio(eps));
        }
        if kind.is_concave() {
            Err(Error::invalid(
                "load",
                format!(
                    "is missing: the {kind} punch needs one of depth, force or contact_ratio \
                     (or eps = b/a)"
                ),
            ))
        } else {
            Ok(Load::Depth(1.0))
        }
    }
}

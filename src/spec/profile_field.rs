//! A surface's `profile` field in a spec: the cosine harmonics as pairs, or the command line's
//! text for a profile (`wavy solve --profile`), which also names a Weierstrass profile.

use crate::profile::{Profile, ProfileError};
use serde::de::{Deserializer, SeqAccess, Visitor};
use serde::Deserialize;

/// `profile = [[1, AR₁], [n, AR₂], …]` (docs/replication.md R13), or `profile = "TEXT"` with
/// the command line's syntax: `"1:AR₁,n:AR₂,…"` or `"weierstrass:AR0,gamma,D,K"` (R14).
#[derive(Debug, Clone, PartialEq)]
pub enum ProfileField {
    /// `(order, aspect ratio)` pairs.
    Harmonics(Vec<(u32, f64)>),
    /// The command line's text.
    Text(String),
}

impl ProfileField {
    /// The profile the field names, or why it names none.
    pub fn profile(&self) -> Result<Profile, ProfileError> {
        match self {
            ProfileField::Harmonics(pairs) => Profile::from_pairs(pairs),
            ProfileField::Text(text) => text.parse(),
        }
    }

    /// The field as a spec error quotes it.
    pub fn quoted(&self) -> String {
        match self {
            ProfileField::Harmonics(pairs) => format!("{pairs:?}"),
            ProfileField::Text(text) => format!("{text:?}"),
        }
    }
}

/// What a spec's `profile` may hold, as a type error says it.
const EXPECTED: &str =
    "a list of [order, aspect ratio] pairs, or a profile text such as \"1:0.1,8:0.05\" or \"weierstrass:0.05,3,1.3,3\"";

struct ProfileFieldVisitor;

impl<'de> Visitor<'de> for ProfileFieldVisitor {
    type Value = ProfileField;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str(EXPECTED)
    }

    fn visit_str<E: serde::de::Error>(self, text: &str) -> Result<ProfileField, E> {
        Ok(ProfileField::Text(text.to_string()))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<ProfileField, A::Error> {
        let mut pairs = Vec::new();
        while let Some(pair) = seq.next_element::<(u32, f64)>()? {
            pairs.push(pair);
        }
        Ok(ProfileField::Harmonics(pairs))
    }
}

impl<'de> Deserialize<'de> for ProfileField {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(ProfileFieldVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pairs and the command line's text name the same profile; a Weierstrass profile is its
    /// harmonics `γᵏ : AR₀ γ^((D−1)k)`; a malformed text is the profile's own error.
    #[test]
    fn pairs_and_text_name_the_same_profile() {
        let pairs: ProfileField = toml::from_str::<toml::Value>("p = [[1, 0.1], [8, 0.05]]")
            .and_then(|v| v["p"].clone().try_into())
            .expect("pairs");
        let text: ProfileField = toml::from_str::<toml::Value>("p = \"1:0.1,8:0.05\"")
            .and_then(|v| v["p"].clone().try_into())
            .expect("text");
        assert_eq!(
            pairs.profile().expect("valid"),
            text.profile().expect("valid")
        );
        let w = ProfileField::Text("weierstrass:0.05,3,1.3,3".into())
            .profile()
            .expect("valid");
        let expected = Profile::from_pairs(&[
            (1, 0.05),
            (3, 0.05 * 3f64.powf(0.3)),
            (9, 0.05 * 9f64.powf(0.3)),
        ])
        .expect("valid");
        for (a, b) in w.harmonics().zip(expected.harmonics()) {
            assert_eq!(a.order, b.order);
            assert!((a.aspect_ratio / b.aspect_ratio - 1.0).abs() < 1e-12);
        }
        assert!(ProfileField::Text("weierstrass:0.05,3".into())
            .profile()
            .is_err());
        let wrong = toml::from_str::<toml::Value>("p = 5").expect("toml")["p"]
            .clone()
            .try_into::<ProfileField>()
            .expect_err("a number is no profile");
        assert!(wrong.to_string().contains("weierstrass:"), "{wrong}");
    }
}

//! What a row of the report is of: a scene ([`SceneId`]) and a [`RowKey`],
//! a [`Method`] a backend renders or a post-process step on NoAA's frame
//! (the `smaa` row, `--post-process`). Rows are looked up by these keys;
//! their names are written only at the output edges (results files,
//! markdown, the page), through `Display`.

use std::fmt;

use subcone_scene::Method;

/// A scene of the run: its unique, file-name-safe name
/// ([`SceneJob::name`](crate::SceneJob::name)). It reads as that name
/// (`Deref` to `str`) where a name is written.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SceneId(String);

impl SceneId {
    /// The scene named `name` (file-name-safe, unique in the run).
    pub fn new(name: impl Into<String>) -> Self {
        SceneId(name.into())
    }

    /// The name.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl std::ops::Deref for SceneId {
    type Target = str;
    fn deref(&self) -> &str {
        &self.0
    }
}

impl PartialEq<str> for SceneId {
    fn eq(&self, other: &str) -> bool {
        self.0 == other
    }
}

impl PartialEq<&str> for SceneId {
    fn eq(&self, other: &&str) -> bool {
        self.0 == *other
    }
}

impl PartialEq<SceneId> for &str {
    fn eq(&self, other: &SceneId) -> bool {
        *self == other.0
    }
}

impl PartialEq<SceneId> for str {
    fn eq(&self, other: &SceneId) -> bool {
        self == other.0
    }
}

impl PartialEq<SceneId> for String {
    fn eq(&self, other: &SceneId) -> bool {
        *self == other.0
    }
}

impl PartialEq<String> for SceneId {
    fn eq(&self, other: &String) -> bool {
        self.0 == *other
    }
}

impl fmt::Display for SceneId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

/// Written as its name: the `scene` field of results.json.
impl serde::Serialize for SceneId {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.0)
    }
}

/// The key of a row beside its scene and backend.
#[derive(Clone, Debug, PartialEq)]
pub enum RowKey {
    /// A method, rendered by the row's backend.
    Method(Method),
    /// A post-process step on NoAA's frame, by its name
    /// ([`PostProcess::name`](crate::post::PostProcess::name)): file-safe and
    /// never a method's name.
    Post(String),
}

impl RowKey {
    /// The method, for a method's row.
    pub fn method(&self) -> Option<Method> {
        match self {
            RowKey::Method(m) => Some(*m),
            RowKey::Post(_) => None,
        }
    }

    /// Whether this is `method`'s row.
    pub fn is(&self, method: Method) -> bool {
        self.method() == Some(method)
    }
}

impl From<Method> for RowKey {
    fn from(m: Method) -> Self {
        RowKey::Method(m)
    }
}

impl PartialEq<Method> for RowKey {
    fn eq(&self, other: &Method) -> bool {
        self.is(*other)
    }
}

/// Written as its name, as `Display` writes it: the `method` field of
/// results.json.
impl serde::Serialize for RowKey {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl fmt::Display for RowKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RowKey::Method(m) => m.fmt(f),
            RowKey::Post(name) => f.write_str(name),
        }
    }
}

/// The key of a method's name, or of a post-process of that name: what
/// the unit tests build their rows from.
#[cfg(test)]
pub(crate) fn named(name: &str) -> RowKey {
    name.parse()
        .map(RowKey::Method)
        .unwrap_or_else(|_| RowKey::Post(name.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use subcone_scene::method::METHOD_NAMES;

    #[test]
    fn a_key_is_written_as_its_name() {
        for name in METHOD_NAMES {
            let m: Method = name.parse().unwrap();
            assert_eq!(RowKey::from(m).to_string(), name);
        }
        assert_eq!(RowKey::Post("smaa".into()).to_string(), "smaa");
        let json = serde_json::json!({ "method": RowKey::from(crate::named::SRAA_RT) });
        assert_eq!(json.to_string(), r#"{"method":"sraa-rt"}"#);
    }

    #[test]
    fn a_scene_id_compares_and_is_written_as_its_name() {
        let id = SceneId::new("cornell");
        // Both orders, each its own `PartialEq` impl.
        assert!(id == "cornell");
        assert!("cornell" == id);
        assert!(id != "atrium");
        assert_eq!(id.to_string(), "cornell");
        let json = serde_json::json!({ "scene": id });
        assert_eq!(json.to_string(), r#"{"scene":"cornell"}"#);
    }

    #[test]
    fn methods_are_equal_exactly_when_their_names_are() {
        // Rows were matched by name before they were keyed by method: the
        // two must agree on every method of the registry.
        let methods: Vec<Method> = METHOD_NAMES.iter().map(|n| n.parse().unwrap()).collect();
        for (a, na) in methods.iter().zip(METHOD_NAMES) {
            let key = RowKey::from(*a);
            for (b, nb) in methods.iter().zip(METHOD_NAMES) {
                assert_eq!(key == *b, na == nb, "{na} against {nb}");
            }
        }
        assert!(RowKey::Post("noaa-like".into()).method().is_none());
        assert_ne!(RowKey::Post("smaa".into()), RowKey::from(methods[0]));
    }
}

//! Parsing scene text into a [`SceneFile`] with the YAML path of any error.

use super::error::SceneError;
use super::schema::SceneFile;

/// Parses scene text with the YAML path of any error.
pub fn parse(text: &str, source: &str) -> Result<SceneFile, SceneError> {
    let de = serde_yaml::Deserializer::from_str(text);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = match e.path().to_string() {
            p if p == "?" || p == "." => "(document)".to_string(),
            p => p,
        };
        let message = e.into_inner().to_string();
        // serde_yaml may start its message with (part of) the path again
        let message = match message.split_once(": ") {
            Some((head, rest)) if path.starts_with(head) => rest.to_string(),
            _ => message,
        };
        SceneError::Parse {
            file: source.to_string(),
            path,
            message,
        }
    })
}

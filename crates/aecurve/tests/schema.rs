//! The protocol's schema as the integration tests apply it: any answer line, and what one
//! command's `--json` prints.

use serde_json::Value;

/// Every error of `v` by `validator`, one string each.
fn errors(validator: &jsonschema::Validator, v: &Value) -> Vec<String> {
    validator.iter_errors(v).map(|e| e.to_string()).collect()
}

/// `v` is a valid response line of the protocol, or the test fails with every error.
pub fn valid_response(v: &Value) {
    static V: std::sync::OnceLock<jsonschema::Validator> = std::sync::OnceLock::new();
    let validator = V.get_or_init(|| {
        jsonschema::validator_for(&aecurve::protocol::response_line_schema())
            .expect("the schema compiles")
    });
    let bad = errors(validator, v);
    assert!(bad.is_empty(), "{v}: {bad:?}");
}

/// `v` is valid by the JSON Schema of the protocol's type `T` (what `--json` prints), or the
/// test fails with every error.
pub fn valid_as<T: schemars::JsonSchema>(v: &Value) {
    let schema = aecurve::protocol::response_schema::<T>();
    let validator = jsonschema::validator_for(&schema).expect("the schema compiles");
    let bad = errors(&validator, v);
    assert!(bad.is_empty(), "{}: {bad:?}", std::any::type_name::<T>());
}

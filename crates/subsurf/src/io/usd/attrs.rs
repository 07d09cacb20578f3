//! Typed reads of one prim's attributes, each failure an [`Error::Usd`] naming the file, the
//! prim and the attribute.

use crate::error::{Error, Result};
use openusd::sdf::{self, AbstractData, Value};

/// A prim of a layer, for reading its attributes.
pub(super) struct PrimReader<'a> {
    pub data: &'a sdf::Data,
    pub file: &'a str,
    pub prim: &'a sdf::Path,
}

impl PrimReader<'_> {
    /// An error about `attribute` of this prim.
    pub fn error(&self, attribute: &str, reason: impl Into<String>) -> Error {
        Error::Usd {
            file: self.file.to_string(),
            prim: self.prim.as_str().to_string(),
            attribute: attribute.to_string(),
            reason: reason.into(),
        }
    }

    fn wrong_type(&self, attribute: &str, expected: &str, found: &Value) -> Error {
        let found: &'static str = found.into();
        self.error(
            attribute,
            format!("expected {expected}, found a {found} value"),
        )
    }

    /// The attribute's spec path.
    pub fn attr_path(&self, name: &str) -> Result<sdf::Path> {
        self.prim
            .append_property(name)
            .map_err(|e| self.error(name, format!("bad property name: {e}")))
    }

    /// A field of the attribute's spec (`default`, `interpolation`, ...), if authored.
    pub fn field(&self, name: &str, field: &str) -> Result<Option<Value>> {
        let path = self.attr_path(name)?;
        if !self.data.has_spec(&path) {
            return Ok(None);
        }
        self.data
            .try_field(&path, field)
            .map(|v| v.map(|v| v.into_owned()))
            .map_err(|e| self.error(name, format!("unreadable {field}: {e}")))
    }

    /// The attribute's value: its default, else its earliest time sample; `None` when
    /// neither is authored (or the value is blocked).
    pub fn value(&self, name: &str) -> Result<Option<Value>> {
        if let Some(v) = self.field(name, "default")? {
            return Ok(Some(v));
        }
        match self.field(name, "timeSamples")? {
            None => Ok(None),
            Some(Value::TimeSamples(samples)) => Ok(samples
                .into_iter()
                .filter(|(t, _)| !t.is_nan())
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .map(|(_, v)| v)),
            Some(other) => Err(self.wrong_type(name, "time samples", &other)),
        }
    }

    /// An integer array (`int[]`; `uint[]` and `int64[]` are accepted where they fit).
    pub fn ints(&self, name: &str) -> Result<Option<Vec<i32>>> {
        let fit = |v: i64| i32::try_from(v).ok();
        let out = match self.value(name)? {
            None | Some(Value::ValueBlock) => return Ok(None),
            Some(Value::IntVec(v)) => return Ok(Some(v)),
            Some(Value::UintVec(v)) => v.iter().map(|&x| fit(x as i64)).collect::<Option<_>>(),
            Some(Value::Int64Vec(v)) => v.iter().map(|&x| fit(x)).collect::<Option<_>>(),
            Some(other) => return Err(self.wrong_type(name, "int[]", &other)),
        };
        out.map(Some)
            .ok_or_else(|| self.error(name, "a value does not fit in a 32-bit integer"))
    }

    /// Non-negative indices below `count`, as `u32`.
    pub fn indices(&self, name: &str, count: usize, what: &str) -> Result<Option<Vec<u32>>> {
        let Some(v) = self.ints(name)? else {
            return Ok(None);
        };
        for (i, &x) in v.iter().enumerate() {
            if x < 0 || x as usize >= count {
                return Err(self.error(
                    name,
                    format!("element {i}: index {x} is out of range (there are {count} {what})"),
                ));
            }
        }
        Ok(Some(v.into_iter().map(|x| x as u32).collect()))
    }

    /// A float array (`float[]`, `double[]` or `half[]`).
    pub fn floats(&self, name: &str) -> Result<Option<Vec<f32>>> {
        Ok(match self.value(name)? {
            None | Some(Value::ValueBlock) => None,
            Some(Value::FloatVec(v)) => Some(v),
            Some(Value::DoubleVec(v)) => Some(v.iter().map(|&x| x as f32).collect()),
            Some(Value::HalfVec(v)) => Some(v.iter().map(|&x| f32::from(x)).collect()),
            Some(other) => return Err(self.wrong_type(name, "float[]", &other)),
        })
    }

    /// A token (a string is accepted too).
    pub fn token(&self, name: &str) -> Result<Option<String>> {
        Ok(match self.value(name)? {
            None | Some(Value::ValueBlock) => None,
            Some(Value::Token(t)) => Some(t.as_str().to_string()),
            Some(Value::String(s)) => Some(s),
            Some(other) => return Err(self.wrong_type(name, "token", &other)),
        })
    }

    /// A token array.
    pub fn tokens(&self, name: &str) -> Result<Option<Vec<String>>> {
        Ok(match self.value(name)? {
            None | Some(Value::ValueBlock) => None,
            Some(Value::TokenVec(v)) => Some(v.iter().map(|t| t.as_str().to_string()).collect()),
            Some(Value::StringVec(v)) => Some(v),
            Some(other) => return Err(self.wrong_type(name, "token[]", &other)),
        })
    }

    /// An array of 3-vectors (`point3f[]`, `float3[]`, `double3[]`, `half3[]`).
    pub fn vec3s(&self, name: &str) -> Result<Option<Vec<[f32; 3]>>> {
        Ok(match self.value(name)? {
            None | Some(Value::ValueBlock) => None,
            Some(Value::Vec3fVec(v)) => Some(v.iter().map(|p| [p.x, p.y, p.z]).collect()),
            Some(Value::Vec3dVec(v)) => Some(
                v.iter()
                    .map(|p| [p.x as f32, p.y as f32, p.z as f32])
                    .collect(),
            ),
            Some(Value::Vec3hVec(v)) => Some(
                v.iter()
                    .map(|p| [f32::from(p.x), f32::from(p.y), f32::from(p.z)])
                    .collect(),
            ),
            Some(other) => return Err(self.wrong_type(name, "point3f[]", &other)),
        })
    }

    /// Points (`point3f[]`, `float3[]`, `half3[]`, or `point3d[]`/`double3[]`, kept in
    /// `f64`).
    pub fn points(&self, name: &str) -> Result<Option<crate::mesh::Positions>> {
        use crate::mesh::Positions;
        Ok(match self.value(name)? {
            Some(Value::Vec3dVec(v)) => Some(Positions::from_f64(
                v.iter().map(|p| [p.x, p.y, p.z]).collect(),
            )),
            _ => self.vec3s(name)?.map(Positions::from_f32),
        })
    }

    /// An array of 2-vectors (`texCoord2f[]`, `float2[]`, `double2[]`, `half2[]`).
    pub fn vec2s(&self, name: &str) -> Result<Option<Vec<[f32; 2]>>> {
        Ok(match self.value(name)? {
            None | Some(Value::ValueBlock) => None,
            Some(Value::Vec2fVec(v)) => Some(v.iter().map(|p| [p.x, p.y]).collect()),
            Some(Value::Vec2dVec(v)) => Some(v.iter().map(|p| [p.x as f32, p.y as f32]).collect()),
            Some(Value::Vec2hVec(v)) => {
                Some(v.iter().map(|p| [f32::from(p.x), f32::from(p.y)]).collect())
            }
            Some(other) => return Err(self.wrong_type(name, "texCoord2f[]", &other)),
        })
    }
}

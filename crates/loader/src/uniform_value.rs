//! A uniform's value as a loader sends it: scalars, vectors, matrices (column-major) and arrays
//! of them, in f64 until the renderer uploads them.

use glam::{DMat3, DMat4, DVec3, DVec4};

/// A uniform value: scalars, vectors, matrices (column-major) and arrays of them.
#[derive(Clone, Debug, PartialEq)]
pub struct Value {
    pub kind: Kind,
    /// Columns (1 for scalars and vectors).
    pub columns: u8,
    /// Rows: vector size (1 for scalars).
    pub rows: u8,
    /// Array length, when an array.
    pub array: Option<u32>,
    /// Components, column-major, element after element; ints stored as their f64 value.
    pub data: Vec<f64>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Float,
    Int,
}

impl Value {
    /// The value with every float component moved by `relative` of itself, ints kept.
    pub fn nudged(&self, relative: f64) -> Value {
        let mut value = self.clone();
        if value.kind == Kind::Float {
            for x in &mut value.data {
                *x *= 1.0 + relative;
            }
        }
        value
    }

    pub fn float(v: f64) -> Value {
        Value { kind: Kind::Float, columns: 1, rows: 1, array: None, data: vec![v] }
    }
    pub fn int(v: i64) -> Value {
        Value { kind: Kind::Int, columns: 1, rows: 1, array: None, data: vec![v as f64] }
    }
    pub fn vec3(v: DVec3) -> Value {
        Value { kind: Kind::Float, columns: 1, rows: 3, array: None, data: v.to_array().to_vec() }
    }
    pub fn vec4(v: DVec4) -> Value {
        Value { kind: Kind::Float, columns: 1, rows: 4, array: None, data: v.to_array().to_vec() }
    }
    pub fn ivec2(x: i64, y: i64) -> Value {
        Value { kind: Kind::Int, columns: 1, rows: 2, array: None, data: vec![x as f64, y as f64] }
    }
    pub fn ivec3(x: i64, y: i64, z: i64) -> Value {
        Value { kind: Kind::Int, columns: 1, rows: 3, array: None, data: vec![x as f64, y as f64, z as f64] }
    }
    pub fn mat4(m: DMat4) -> Value {
        Value { kind: Kind::Float, columns: 4, rows: 4, array: None, data: m.to_cols_array().to_vec() }
    }
    pub fn mat3(m: DMat3) -> Value {
        Value { kind: Kind::Float, columns: 3, rows: 3, array: None, data: m.to_cols_array().to_vec() }
    }
    pub fn mat4_array(ms: &[DMat4]) -> Value {
        Value {
            kind: Kind::Float,
            columns: 4,
            rows: 4,
            array: Some(ms.len() as u32),
            data: ms.iter().flat_map(|m| m.to_cols_array()).collect(),
        }
    }

    /// The GLSL type this value fills.
    pub fn glsl_type(&self) -> String {
        let base = match (self.kind, self.columns, self.rows) {
            (Kind::Float, 1, 1) => "float".to_string(),
            (Kind::Int, 1, 1) => "int".to_string(),
            (Kind::Float, 1, n) => format!("vec{n}"),
            (Kind::Int, 1, n) => format!("ivec{n}"),
            (_, c, r) if c == r => format!("mat{c}"),
            (_, c, r) => format!("mat{c}x{r}"),
        };
        match self.array {
            Some(n) => format!("{base}[{n}]"),
            None => base,
        }
    }

    /// The value as a GLSL constructor valid in GLSL 1.20 and later (`0`, `vec3(0.5, 1.0, 2.0)`),
    /// each float written so that it parses back to the same f32 the uniform buffer holds.
    /// `None` for arrays, which have no constructor in GLSL 1.20.
    pub fn glsl_initialiser(&self) -> Option<String> {
        if self.array.is_some() {
            return None;
        }
        let parts: Vec<String> = match self.kind {
            Kind::Float => self.as_f32().iter().map(|v| format!("{v:?}")).collect(),
            Kind::Int => self.as_i32().iter().map(i32::to_string).collect(),
        };
        Some(if parts.len() == 1 { parts[0].clone() } else { format!("{}({})", self.glsl_type(), parts.join(", ")) })
    }

    /// Components as f32 (for OpenGL's glUniform*fv).
    pub fn as_f32(&self) -> Vec<f32> {
        self.data.iter().map(|&v| v as f32).collect()
    }

    pub fn as_i32(&self) -> Vec<i32> {
        self.data.iter().map(|&v| v as i32).collect()
    }
}

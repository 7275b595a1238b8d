//! naga's messages in the pack's terms, for `validate` and `render` alike: the lowering's reserved names turned back into the
//! GLSL names they stand for, and what naga cannot check said as such.

use crate::{Code, Diagnostic, Severity};

/// Speaks of the pack's names instead of the lowering's reserved ones in naga's messages, and
/// explains the messages that the lowering makes obscure.
pub fn clarify(mut diag: Diagnostic) -> Diagnostic {
    diag.message = crate::lower::unlower_names(&diag.message);
    let sampling = ["texture", "textureLod", "textureProj", "textureGrad", "texelFetch", "textureSize", "textureOffset"];
    // naga names a built-in whose arguments fit none of its own forms by its IR name (`Dot`).
    let invalid_arguments = diag
        .message
        .strip_prefix("Can't resolve type: BuiltinArgumentsInvalid(\"")
        .and_then(|r| r.strip_suffix("\")"))
        .and_then(|ir_name| BUILTIN_FORMS.iter().find(|(builtin, _)| builtin.eq_ignore_ascii_case(ir_name)))
        .map(|(builtin, _)| builtin.to_string());
    let unknown =
        diag.message.strip_prefix("Unknown function '").and_then(|r| r.strip_suffix('\'')).map(str::to_string).or(invalid_arguments);
    let unknown_variable = diag.message.strip_prefix("Unknown variable: ").map(str::to_string);
    if let Some(name) = unknown.as_deref().or(unknown_variable.as_deref())
        && NAGA_LACKS.iter().any(|prefix| name.starts_with(prefix))
    {
        // Valid GLSL naga's front-end does not implement: not the pack's mistake.
        let call = if unknown.is_some() { "()" } else { "" };
        diag.severity = Severity::Warning;
        diag.code = Code::NotChecked;
        diag.message = format!("{name}{call} is not checked: naga's GLSL front-end does not implement it (`--driver` compiles it with Mesa)");
        return diag;
    }
    if let Some((operator, size)) = crate::naga_check::logical_operator_on_vectors(&diag.message) {
        diag.message = format!(
            "`{operator}` takes two bools, and here it meets bvec{size}s: GLSL has no `{operator}` of vectors (NVIDIA applies it to each component; elsewhere write `any()`, `all()`, or `notEqual(ivec{size}(a) + ivec{size}(b), ivec{size}(0))`)"
        );
        return diag;
    }
    if let Some(what) = diag.message.strip_prefix("Not implemented: ") {
        // Valid GLSL naga's front-end has no code for: not the pack's mistake.
        let what = what.to_string();
        diag.severity = Severity::Warning;
        diag.code = Code::NotChecked;
        diag.message = format!("this {what} is not checked: naga's GLSL front-end does not implement it, so the rest of this stage is not checked (`--driver` compiles it with Mesa)");
        return diag;
    }
    if let Some(name) = unknown_variable.as_deref() {
        // In the words GLSL compilers use (glslang: "undeclared identifier").
        diag.message = format!("undeclared identifier `{name}`: no variable of this name is declared where it is used");
        return diag;
    }
    if let Some(value) = ["NaN", "infinite"].into_iter().find(|v| diag.message.contains(&format!("Float literal is {v}"))) {
        // naga refuses a constant that folds to NaN or infinity; GLSL compilers fold it and
        // compile (Mesa does), and the value reaches whatever reads it.
        let value = if value == "NaN" { "NaN" } else { "infinite" };
        diag.severity = Severity::Warning;
        diag.code = Code::NotChecked;
        diag.message = format!(
            "a constant expression here is {value} (such as 0.0 / 0.0 from option values): drivers compile it and the \
             value is {value} wherever it is used; naga stops here, so the rest of this stage is not checked"
        );
        return diag;
    }
    if diag.message.contains("unsupported matrix of the form matCx2") {
        // A two-row matrix in a block, a struct of one, or a struct varying: GLSL lays it out
        // and drivers accept it; naga's std140 layout has no two-row matrices.
        diag.severity = Severity::Warning;
        diag.code = Code::NotChecked;
        diag.message = "a two-row matrix (mat2, mat3x2, mat4x2) here is not checked: naga cannot lay one out in a block \
                        or a struct, drivers accept it (`--driver` compiles it with Mesa)"
            .into();
        return diag;
    }
    if diag.message.contains("Unable to operate on image class Sampled { kind: Uint")
        || diag.message.contains("Unable to operate on image class Sampled { kind: Sint")
    {
        // GLSL samples integer textures (nearest texel); naga only loads from them.
        diag.severity = Severity::Warning;
        diag.code = Code::NotChecked;
        diag.message = "sampling an integer texture (isampler*/usampler*) is not checked: naga refuses it, drivers \
                        accept it (`--driver` compiles it with Mesa)"
            .into();
        return diag;
    }
    if unknown.as_deref().is_some_and(|name| {
        sampling.contains(&name)
            || matches!(name, "imageLoad" | "imageStore" | "imageSize")
            || name.starts_with("atomic")
            || BUILTIN_FORMS.iter().any(|(builtin, _)| *builtin == name)
    }) {
        diag.code = Code::NoMatchingOverload;
    }
    if let Some(name) = unknown.as_deref()
        && sampling.contains(&name)
    {
        diag = diag.with_note(format!(
            "no form of {name}() (texture2D, shadow2D, … in old GLSL) takes these arguments: check the sampler's type \
             (sampler2D, sampler2DShadow, sampler3D, …) against the coordinates"
        ));
    } else if let Some(name) = unknown.as_deref()
        && matches!(name, "imageLoad" | "imageStore" | "imageSize")
    {
        diag = diag.with_note(format!(
            "no form of {name}() takes these arguments: check the image's type (image2D, uimage2D, image3D, …) against \
             the coordinates (ivec2 for image2D) and the value (vec4 for image*, uvec4 for uimage*, ivec4 for iimage*)"
        ));
    } else if let Some((name, forms)) =
        unknown.as_deref().and_then(|name| BUILTIN_FORMS.iter().find(|(builtin, _)| *builtin == name))
    {
        // naga says a built-in called with arguments no form takes is unknown.
        diag.message = format!("no form of the built-in {name}() takes these arguments");
        diag = diag.with_note(format!("GLSL has {name}({})", forms.replace("; ", &format!("), {name}("))));
        if forms.contains("gen") {
            diag = diag.with_note(
                "genType is float, vec2, vec3 or vec4 (genIType int, ivec…; genUType uint, uvec…; genBType bool, bvec…), the same \
                 type at every place of one form; GLSL 1.20 converts int arguments to float, not vectors to other sizes",
            );
        }
    } else if let Some(name) = unknown.as_deref()
        && name.starts_with("atomic")
    {
        diag = diag.with_note(format!("no form of {name}() takes these arguments: atomics take an int or uint variable (shared or in a buffer) and an int or uint value"));
    } else if let Some(name) = unknown.as_deref()
        && diag.message.starts_with("Unknown function '")
    {
        // Neither a built-in nor a function the pack declares (those get their own message).
        diag.message = format!("undeclared function `{name}`: no function of this name is declared before this call");
    }
    diag
}

/// The forms of GLSL's common built-in functions, as the GLSL specification lists them (each
/// form's parameters, forms separated by `; `), for a call naga finds no form for.
const BUILTIN_FORMS: &[(&str, &str)] = &[
    ("radians", "genType degrees"),
    ("degrees", "genType radians"),
    ("sin", "genType angle"),
    ("cos", "genType angle"),
    ("tan", "genType angle"),
    ("asin", "genType x"),
    ("acos", "genType x"),
    ("atan", "genType y, genType x; genType y_over_x"),
    ("pow", "genType x, genType y"),
    ("exp", "genType x"),
    ("log", "genType x"),
    ("exp2", "genType x"),
    ("log2", "genType x"),
    ("sqrt", "genType x"),
    ("inversesqrt", "genType x"),
    ("abs", "genType x; genIType x"),
    ("sign", "genType x; genIType x"),
    ("floor", "genType x"),
    ("ceil", "genType x"),
    ("fract", "genType x"),
    ("round", "genType x"),
    ("trunc", "genType x"),
    ("mod", "genType x, float y; genType x, genType y"),
    ("min", "genType x, genType y; genType x, float y; genIType x, genIType y; genIType x, int y; genUType x, genUType y; genUType x, uint y"),
    ("max", "genType x, genType y; genType x, float y; genIType x, genIType y; genIType x, int y; genUType x, genUType y; genUType x, uint y"),
    ("clamp", "genType x, genType minVal, genType maxVal; genType x, float minVal, float maxVal; genIType x, genIType minVal, genIType maxVal; genIType x, int minVal, int maxVal"),
    ("mix", "genType x, genType y, genType a; genType x, genType y, float a; genType x, genType y, genBType a"),
    ("step", "genType edge, genType x; float edge, genType x"),
    ("smoothstep", "genType edge0, genType edge1, genType x; float edge0, float edge1, genType x"),
    ("length", "genType x"),
    ("distance", "genType p0, genType p1"),
    ("dot", "genType x, genType y"),
    ("cross", "vec3 x, vec3 y"),
    ("normalize", "genType x"),
    ("faceforward", "genType N, genType I, genType Nref"),
    ("reflect", "genType I, genType N"),
    ("refract", "genType I, genType N, float eta"),
    ("matrixCompMult", "mat x, mat y"),
    ("transpose", "mat m"),
    ("inverse", "mat m"),
    ("determinant", "mat m"),
    ("outerProduct", "vec c, vec r"),
    ("dFdx", "genType p"),
    ("dFdy", "genType p"),
    ("fwidth", "genType p"),
    ("texture2D", "sampler2D sampler, vec2 coord; sampler2D sampler, vec2 coord, float bias"),
    ("texture2DLod", "sampler2D sampler, vec2 coord, float lod"),
    ("texture3D", "sampler3D sampler, vec3 coord; sampler3D sampler, vec3 coord, float bias"),
    ("shadow2D", "sampler2DShadow sampler, vec3 coord; sampler2DShadow sampler, vec3 coord, float bias"),
];

/// Built-in functions and variables (by prefix) naga's GLSL front-end lacks and the lowering has
/// no stand-in for: image atomics (images cannot be function parameters in naga), atomic
/// counters, the subgroup built-ins of `GL_KHR_shader_subgroup_*`, and the `textureGather*` and
/// `textureQueryLod` forms the lowering has no stand-in for (other sampler types).
const NAGA_LACKS: [&str; 6] = ["imageAtomic", "atomicCounter", "subgroup", "gl_Subgroup", "textureGather", "textureQueryLod"];

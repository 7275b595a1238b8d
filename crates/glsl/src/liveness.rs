//! Which global variables a stage reads in a way that can reach its results: what is left of
//! the stage after a driver's optimiser drops the code whose values go nowhere.
//!
//! Mesa's linker judges a fragment input the vertex stage never writes only after that
//! optimisation (GLSL 1.10/1.20: "fragment shader varying … not written by vertex shader"): a
//! read passed to a function parameter the function ignores, or stored to a variable nothing
//! reads, is gone by then and the program links. This analysis follows values backwards from
//! what a stage leaves behind (its outputs, `discard`, stores to buffers and images) through
//! stores, loads, calls and control flow, over naga's IR. It keeps every value that may reach a
//! result: it folds no constants, so it can only keep more than the optimiser does.
//!
//! Beside it, [`reads_beyond_first_channel`]: whether a texture's lookups are used past their
//! first channel, which decides how a renderer must bind a depth buffer read as a colour.

use std::collections::HashSet;

use naga::{AddressSpace, Block, Expression, Function, Handle, Module, SampleLevel, Statement};

/// The names of the global variables of `module` whose value, as loaded, can reach a result of
/// its entry points.
pub fn live_global_names(module: &Module) -> HashSet<String> {
    let mut analysis = Analysis::new(module);
    analysis.run();
    analysis.live_globals.iter().filter_map(|&g| module.global_variables[g].name.clone()).collect()
}

/// What is known live, per function (indexed as `module.functions`, the entry points after).
#[derive(Default, Clone)]
struct FunctionFacts {
    expressions: HashSet<Handle<Expression>>,
    locals: HashSet<Handle<naga::LocalVariable>>,
    /// Arguments whose value reaches a result.
    params: HashSet<u32>,
    /// Pointer arguments the function reads through.
    read_pointers: HashSet<u32>,
    /// Pointer arguments whose pointee is live in some caller: stores through them count.
    live_out_pointers: HashSet<u32>,
    result_live: bool,
    /// The function does something that reaches a result.
    has_effect: bool,
}

struct Analysis<'m> {
    module: &'m Module,
    functions: Vec<&'m Function>,
    /// Handles of `module.functions`, in order, for `Statement::Call`.
    handles: Vec<Handle<Function>>,
    facts: Vec<FunctionFacts>,
    live_globals: HashSet<Handle<naga::GlobalVariable>>,
    changed: bool,
}

/// Where a pointer expression points: the variable at the root of its access chain.
enum Root {
    Global(Handle<naga::GlobalVariable>),
    Local(Handle<naga::LocalVariable>),
    Argument(u32),
    Unknown,
}

impl<'m> Analysis<'m> {
    fn new(module: &'m Module) -> Self {
        let handles: Vec<Handle<Function>> = module.functions.iter().map(|(h, _)| h).collect();
        let mut functions: Vec<&Function> = module.functions.iter().map(|(_, f)| f).collect();
        let entry_start = functions.len();
        functions.extend(module.entry_points.iter().map(|e| &e.function));
        let mut facts = vec![FunctionFacts::default(); functions.len()];
        // An entry point's result is what the stage leaves behind.
        for fact in &mut facts[entry_start..] {
            fact.result_live = true;
        }
        Analysis { module, functions, handles, facts, live_globals: HashSet::new(), changed: true }
    }

    fn run(&mut self) {
        // Every step only adds facts, so this ends.
        while self.changed {
            self.changed = false;
            for f in 0..self.functions.len() {
                let function = self.functions[f];
                let effect = self.walk(f, &function.body, false);
                if effect && !self.facts[f].has_effect {
                    self.facts[f].has_effect = true;
                    self.changed = true;
                }
                self.propagate(f);
            }
        }
    }

    fn root(function: &Function, mut pointer: Handle<Expression>) -> Root {
        loop {
            match function.expressions[pointer] {
                Expression::Access { base, .. } | Expression::AccessIndex { base, .. } => pointer = base,
                Expression::GlobalVariable(g) => return Root::Global(g),
                Expression::LocalVariable(l) => return Root::Local(l),
                Expression::FunctionArgument(i) => return Root::Argument(i),
                _ => return Root::Unknown,
            }
        }
    }

    /// The index expressions along a pointer's access chain, which choose what is stored.
    fn chain_indices(function: &Function, mut pointer: Handle<Expression>) -> Vec<Handle<Expression>> {
        let mut indices = Vec::new();
        loop {
            match function.expressions[pointer] {
                Expression::Access { base, index } => {
                    indices.push(index);
                    pointer = base;
                }
                Expression::AccessIndex { base, .. } => pointer = base,
                _ => return indices,
            }
        }
    }

    fn mark(&mut self, f: usize, expression: Handle<Expression>) {
        if self.facts[f].expressions.insert(expression) {
            self.changed = true;
        }
    }

    /// Whether a store through `pointer` in function `f` lands where a result can see it.
    fn store_is_live(&self, f: usize, pointer: Handle<Expression>) -> bool {
        match Self::root(self.functions[f], pointer) {
            Root::Global(g) => {
                let space = self.module.global_variables[g].space;
                self.live_globals.contains(&g) || !matches!(space, AddressSpace::Private | AddressSpace::Function | AddressSpace::WorkGroup)
            }
            Root::Local(l) => self.facts[f].locals.contains(&l),
            Root::Argument(i) => self.facts[f].live_out_pointers.contains(&i),
            // Through something this analysis does not follow: kept.
            Root::Unknown => true,
        }
    }

    /// Walks a block, marking what its live statements need; whether it holds anything that
    /// reaches a result. `in_live_loop`: a `break` or `continue` here changes what a live loop
    /// does.
    fn walk(&mut self, f: usize, block: &Block, in_live_loop: bool) -> bool {
        let function = self.functions[f];
        let mut effect = false;
        for statement in block.iter() {
            match *statement {
                Statement::Emit(_) | Statement::ControlBarrier(_) | Statement::MemoryBarrier(_) => {}
                Statement::Block(ref inner) => effect |= self.walk(f, inner, in_live_loop),
                Statement::If { condition, ref accept, ref reject } => {
                    let branches = self.walk(f, accept, in_live_loop) | self.walk(f, reject, in_live_loop);
                    if branches {
                        self.mark(f, condition);
                        effect = true;
                    }
                }
                Statement::Switch { selector, ref cases } => {
                    let mut any = false;
                    for case in cases {
                        any |= self.walk(f, &case.body, true);
                    }
                    if any {
                        self.mark(f, selector);
                        effect = true;
                    }
                }
                Statement::Loop { ref body, ref continuing, break_if } => {
                    let live = self.walk(f, body, false) | self.walk(f, continuing, false);
                    if live {
                        self.walk(f, body, true);
                        self.walk(f, continuing, true);
                        if let Some(condition) = break_if {
                            self.mark(f, condition);
                        }
                        effect = true;
                    }
                }
                Statement::Break | Statement::Continue => effect |= in_live_loop,
                Statement::Return { value: Some(value) } => {
                    if self.facts[f].result_live {
                        self.mark(f, value);
                        effect = true;
                    }
                }
                // An early return decides whether what follows it runs.
                Statement::Return { value: None } => effect |= self.facts[f].has_effect,
                Statement::Kill => effect = true,
                Statement::Store { pointer, value } => {
                    if self.store_is_live(f, pointer) {
                        self.mark(f, value);
                        for index in Self::chain_indices(function, pointer) {
                            self.mark(f, index);
                        }
                        effect = true;
                    }
                }
                Statement::Call { function: callee, ref arguments, result } => {
                    let Some(c) = self.handles.iter().position(|h| *h == callee) else { continue };
                    if result.is_some_and(|r| self.facts[f].expressions.contains(&r)) && !self.facts[c].result_live {
                        self.facts[c].result_live = true;
                        self.changed = true;
                    }
                    for (i, &argument) in arguments.iter().enumerate() {
                        let i = i as u32;
                        if self.facts[c].params.contains(&i) {
                            self.mark(f, argument);
                        }
                        let pointee_live = self.store_is_live(f, argument) && !matches!(Self::root(function, argument), Root::Unknown);
                        if pointee_live && self.facts[c].live_out_pointers.insert(i) {
                            self.changed = true;
                        }
                        if self.facts[c].read_pointers.contains(&i) {
                            self.mark(f, argument);
                        }
                    }
                    effect |= self.facts[c].has_effect;
                }
                // Images, atomics and the rest write memory others see: kept whole.
                _ => {
                    effect = true;
                    for expression in statement_operands(statement) {
                        self.mark(f, expression);
                    }
                }
            }
        }
        effect
    }

    /// Marks what the live expressions of function `f` read, until nothing more is marked.
    fn propagate(&mut self, f: usize) {
        let function = self.functions[f];
        let mut pending: Vec<Handle<Expression>> = self.facts[f].expressions.iter().copied().collect();
        let mut seen: HashSet<Handle<Expression>> = HashSet::new();
        while let Some(expression) = pending.pop() {
            if !seen.insert(expression) {
                continue;
            }
            if self.facts[f].expressions.insert(expression) {
                self.changed = true;
            }
            // A live variable or argument is one whose value is read (a store's pointer is
            // never marked, only the indices that choose where it lands).
            let node = &function.expressions[expression];
            let added = match *node {
                Expression::GlobalVariable(g) => self.live_globals.insert(g),
                Expression::LocalVariable(l) => {
                    pending.extend(function.local_variables[l].init);
                    self.facts[f].locals.insert(l)
                }
                Expression::FunctionArgument(i) => {
                    let ty = function.arguments[i as usize].ty;
                    if matches!(self.module.types[ty].inner, naga::TypeInner::Pointer { .. }) {
                        self.facts[f].read_pointers.insert(i)
                    } else {
                        self.facts[f].params.insert(i)
                    }
                }
                _ => false,
            };
            self.changed |= added;
            pending.extend(expression_operands(node));
        }
    }
}

/// Whether `module` uses more than the first channel of a lookup of the texture `global`
/// (`texture(depthtex0, uv).r` uses the first alone; `.rgb`, `.a` or the whole vector more).
pub fn reads_beyond_first_channel(module: &Module, global: Handle<naga::GlobalVariable>) -> bool {
    let functions = module.functions.iter().map(|(_, f)| f).chain(module.entry_points.iter().map(|e| &e.function));
    functions.into_iter().any(|function| {
        let lookups: HashSet<Handle<Expression>> = function
            .expressions
            .iter()
            .filter(|(_, e)| match **e {
                Expression::ImageSample { image, .. } | Expression::ImageLoad { image, .. } => {
                    matches!(function.expressions[image], Expression::GlobalVariable(g) if g == global)
                }
                _ => false,
            })
            .map(|(h, _)| h)
            .collect();
        if lookups.is_empty() {
            return false;
        }
        let first_only = |e: &Expression| match *e {
            Expression::AccessIndex { index: 0, .. } => true,
            Expression::Swizzle { size, pattern, .. } => pattern[..size as usize].iter().all(|c| *c == naga::SwizzleComponent::X),
            _ => false,
        };
        let beyond_in_expressions =
            function.expressions.iter().any(|(_, e)| !first_only(e) && expression_operands(e).iter().any(|o| lookups.contains(o)));
        beyond_in_expressions || block_uses_whole(&function.body, &lookups)
    })
}

/// Whether a statement of `block` takes one of `values` whole (stores it, passes it, returns it).
fn block_uses_whole(block: &Block, values: &HashSet<Handle<Expression>>) -> bool {
    block.iter().any(|statement| match *statement {
        Statement::Block(ref inner) => block_uses_whole(inner, values),
        Statement::If { ref accept, ref reject, .. } => block_uses_whole(accept, values) || block_uses_whole(reject, values),
        Statement::Switch { ref cases, .. } => cases.iter().any(|c| block_uses_whole(&c.body, values)),
        Statement::Loop { ref body, ref continuing, .. } => block_uses_whole(body, values) || block_uses_whole(continuing, values),
        Statement::Store { value, .. } => values.contains(&value),
        Statement::Return { value: Some(value) } => values.contains(&value),
        Statement::Call { ref arguments, .. } => arguments.iter().any(|a| values.contains(a)),
        _ => statement_operands(statement).iter().any(|o| values.contains(o)),
    })
}

/// The expressions an expression reads.
pub fn expression_operands(expression: &Expression) -> Vec<Handle<Expression>> {
    use Expression as E;
    let mut operands = Vec::new();
    match *expression {
        E::Compose { ref components, .. } => operands.extend(components.iter().copied()),
        E::Access { base, index } => operands.extend([base, index]),
        E::AccessIndex { base, .. } => operands.push(base),
        E::Splat { value, .. } => operands.push(value),
        E::Swizzle { vector, .. } => operands.push(vector),
        E::Load { pointer } => operands.push(pointer),
        E::ImageSample { image, sampler, coordinate, array_index, offset, ref level, depth_ref, .. } => {
            operands.extend([image, sampler, coordinate]);
            operands.extend(array_index);
            operands.extend(offset);
            operands.extend(depth_ref);
            match *level {
                SampleLevel::Exact(e) | SampleLevel::Bias(e) => operands.push(e),
                SampleLevel::Gradient { x, y } => operands.extend([x, y]),
                SampleLevel::Auto | SampleLevel::Zero => {}
            }
        }
        E::ImageLoad { image, coordinate, array_index, sample, level } => {
            operands.extend([image, coordinate]);
            operands.extend(array_index);
            operands.extend(sample);
            operands.extend(level);
        }
        E::ImageQuery { image, ref query } => {
            operands.push(image);
            if let naga::ImageQuery::Size { level: Some(level) } = *query {
                operands.push(level);
            }
        }
        E::Unary { expr, .. } | E::Derivative { expr, .. } | E::As { expr, .. } | E::ArrayLength(expr) => operands.push(expr),
        E::Relational { argument, .. } => operands.push(argument),
        E::Binary { left, right, .. } => operands.extend([left, right]),
        E::Select { condition, accept, reject } => operands.extend([condition, accept, reject]),
        E::Math { arg, arg1, arg2, arg3, .. } => {
            operands.push(arg);
            operands.extend(arg1);
            operands.extend(arg2);
            operands.extend(arg3);
        }
        // Leaves, results given by statements, and what fragment stages of shader packs never hold.
        _ => {}
    }
    operands
}

/// The expressions a statement with side effects this analysis keeps whole reads.
fn statement_operands(statement: &Statement) -> Vec<Handle<Expression>> {
    match *statement {
        Statement::ImageStore { image, coordinate, array_index, value } => {
            let mut operands = vec![image, coordinate, value];
            operands.extend(array_index);
            operands
        }
        Statement::Atomic { pointer, value, .. } => vec![pointer, value],
        Statement::ImageAtomic { image, coordinate, array_index, value, .. } => {
            let mut operands = vec![image, coordinate, value];
            operands.extend(array_index);
            operands
        }
        Statement::WorkGroupUniformLoad { pointer, .. } => vec![pointer],
        _ => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fragment_module(text: &str) -> Module {
        let options = naga::front::glsl::Options::from(naga::ShaderStage::Fragment);
        naga::front::glsl::Frontend::default().parse(&options, text).expect("parses")
    }

    fn live(fragment: &str) -> HashSet<String> {
        live_global_names(&fragment_module(fragment))
    }

    const HEAD: &str = "#version 450\nlayout(location = 0) in vec3 a;\nlayout(location = 1) in vec3 b;\nlayout(location = 0) out vec4 color;\n";

    #[test]
    fn a_read_that_reaches_the_output_is_live_and_one_that_does_not_is_not() {
        let found = live(&format!("{HEAD}void main() {{ vec3 unused = b * 2.0; color = vec4(a, 1.0); }}\n"));
        assert!(found.contains("a") && !found.contains("b"), "{found:?}");
    }

    #[test]
    fn a_parameter_the_function_ignores_carries_nothing() {
        let text = format!(
            "{HEAD}vec3 shade(vec3 light, vec3 ambient) {{ return ambient * 0.5; }}\nvoid main() {{ color = vec4(shade(b, a), 1.0); }}\n"
        );
        let found = live(&text);
        assert!(found.contains("a") && !found.contains("b"), "{found:?}");
    }

    #[test]
    fn values_reach_the_output_through_variables_out_parameters_and_conditions() {
        let text = format!(
            "{HEAD}void fill(out vec3 target, vec3 from) {{ target = from; }}\n\
             void main() {{ vec3 v; fill(v, a); if (b.x > 0.0) {{ v *= 2.0; }} color = vec4(v, 1.0); }}\n"
        );
        let found = live(&text);
        assert!(found.contains("a") && found.contains("b"), "{found:?}");
    }

    #[test]
    fn a_condition_around_discard_is_live_and_one_around_nothing_is_not() {
        let found = live(&format!("{HEAD}void main() {{ if (a.x > 0.0) discard; if (b.x > 0.0) {{ float t = 1.0; }} color = vec4(1.0); }}\n"));
        assert!(found.contains("a") && !found.contains("b"), "{found:?}");
    }

    #[test]
    fn a_depth_lookup_used_past_its_first_channel_is_told_apart() {
        let beyond = |body: &str| {
            let module = fragment_module(&format!("#version 450\nlayout(set = 0, binding = 0) uniform texture2D depth;\nlayout(set = 0, binding = 1) uniform sampler s;\nlayout(location = 0) out vec4 color;\nvoid main() {{ {body} }}\n"));
            let global = module.global_variables.iter().find(|(_, g)| g.name.as_deref() == Some("depth")).expect("declared").0;
            reads_beyond_first_channel(&module, global)
        };
        assert!(!beyond("color = vec4(texture(sampler2D(depth, s), vec2(0.5)).r);"));
        assert!(!beyond("color = texture(sampler2D(depth, s), vec2(0.5)).xxxx;"));
        assert!(beyond("color = vec4(texture(sampler2D(depth, s), vec2(0.5)).rgb, 1.0);"));
        assert!(beyond("color = texture(sampler2D(depth, s), vec2(0.5));"));
        assert!(beyond("vec4 d = texture(sampler2D(depth, s), vec2(0.5)); color = vec4(d.a);"));
    }

    #[test]
    fn a_loop_whose_body_writes_the_output_keeps_its_exit_condition() {
        let text = format!("{HEAD}void main() {{ color = vec4(0.0); for (int i = 0; i < 4; i++) {{ if (b[i % 3] > 0.5) break; color += vec4(a, 1.0); }} }}\n");
        let found = live(&text);
        assert!(found.contains("a") && found.contains("b"), "{found:?}");
    }
}

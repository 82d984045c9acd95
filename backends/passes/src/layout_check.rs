//! The layout check shared by `subcone-passes`' and `subcone-wgpu`'s layout
//! tests (`layout_tests.rs` in each): a `#[repr(C)]` struct against its WGSL
//! twin through naga's layouter. Test-only; `subcone-wgpu` includes this file
//! by path.

/// The text of `struct <name> { … }` in `source`.
fn struct_text<'a>(source: &'a str, name: &str) -> &'a str {
    let start = source
        .find(&format!("struct {name} {{"))
        .unwrap_or_else(|| panic!("no struct {name} in the WGSL"));
    let end = start + source[start..].find('}').expect("closing brace") + 1;
    &source[start..end]
}

/// One Rust field as WGSL members: (WGSL name, offset, size).
pub(crate) type Member = (String, usize, usize);

/// `members!(T: field, field, pad[N] as f32, …)`: a field is the WGSL member
/// of the same name; `pad[N] as E` is N scalar members `pad0` … of type E.
macro_rules! members {
    ($ty:ty: $($field:ident $([$n:literal as $e:ty])?),+ $(,)?) => {{
        let mut m: Vec<Member> = Vec::new();
        $( members!(@one m, $ty, $field $([$n as $e])?); )+
        m
    }};
    (@one $m:ident, $ty:ty, $field:ident) => {{
        let probe = |s: &$ty| core::mem::size_of_val(&s.$field);
        let size = probe(&bytemuck::Zeroable::zeroed());
        $m.push((stringify!($field).to_string(), core::mem::offset_of!($ty, $field), size));
    }};
    (@one $m:ident, $ty:ty, $field:ident [$n:literal as $e:ty]) => {{
        for i in 0..$n {
            $m.push((
                format!("{}{i}", stringify!($field)),
                core::mem::offset_of!($ty, $field) + i * core::mem::size_of::<$e>(),
                core::mem::size_of::<$e>(),
            ));
        }
    }};
}

/// One struct to check: the WGSL source declaring it, its WGSL name, the
/// Rust struct's size and members (`members!`).
pub(crate) type Check<'a> = (&'a str, &'a str, usize, Vec<Member>);

/// [`compare`] every struct of `checks`; panics listing every mismatch.
pub(crate) fn assert_all_match(checks: &[Check<'_>]) {
    let errors: Vec<String> = checks
        .iter()
        .filter_map(|(src, name, size, m)| compare(src, name, *size, m).err())
        .collect();
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}

/// Compare the WGSL struct `wgsl_name` (declared in `source`, after the
/// kernels' shared structs) with the Rust layout `members` of total `size`.
pub(crate) fn compare(
    source: &str,
    wgsl_name: &str,
    size: usize,
    members: &[Member],
) -> Result<(), String> {
    let text = format!(
        "{}\n{}\n",
        subcone_kernels::wgsl::PARAMS,
        struct_text(source, wgsl_name)
    );
    let module = naga::front::wgsl::parse_str(&text).map_err(|e| e.emit_to_string(&text))?;
    let mut layouter = naga::proc::Layouter::default();
    layouter
        .update(module.to_ctx())
        .map_err(|e| e.to_string())?;
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(wgsl_name))
        .ok_or_else(|| format!("no WGSL struct {wgsl_name}"))?;
    let naga::TypeInner::Struct {
        members: wgsl,
        span,
    } = &ty.inner
    else {
        return Err(format!("{wgsl_name} is not a struct"));
    };
    let names: Vec<&str> = wgsl
        .iter()
        .map(|m| m.name.as_deref().unwrap_or("?"))
        .collect();
    let rust: Vec<&str> = members.iter().map(|m| m.0.as_str()).collect();
    if names != rust {
        return Err(format!(
            "{wgsl_name}: WGSL members {names:?}, Rust {rust:?}"
        ));
    }
    for (w, (name, offset, bytes)) in wgsl.iter().zip(members) {
        let wsize = layouter[w.ty].size as usize;
        if w.offset as usize != *offset || wsize != *bytes {
            return Err(format!(
                "{wgsl_name}.{name}: WGSL offset {} size {wsize}, Rust offset {offset} size {bytes}",
                w.offset
            ));
        }
    }
    if *span as usize != size || layouter[handle].size as usize != size {
        return Err(format!("{wgsl_name}: WGSL size {span}, Rust size {size}"));
    }
    Ok(())
}

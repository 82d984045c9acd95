//! The conversions between a C struct and the kernels' struct it mirrors.

/// `From` both ways between a C struct and the kernels' struct it mirrors,
/// from one list of `c_field: kernels_field` pairs: both directions convert
/// the same fields, and a field added to either struct and not listed is a
/// compile error (a struct literal must name every field).
macro_rules! mirror_conversions {
    ($c:ident <=> $k:ident { $($cf:ident: $kf:ident),+ $(,)? }) => {
        impl From<$c> for $k {
            fn from(p: $c) -> $k {
                $k { $($kf: p.$cf),+ }
            }
        }

        impl From<$k> for $c {
            fn from(p: $k) -> $c {
                $c { $($cf: p.$kf),+ }
            }
        }
    };
}

//! Typed indices into the workspace's packed tables, each with one invalid value, `NONE`
//! ("no such item"), so that a table of ids needs no `Option` and no sentinel of its own.

/// Defines an index type: a `u32` whose `u32::MAX` is `NONE`.
macro_rules! index_type {
    ($(#[$doc:meta])* $vis:vis struct $name:ident;) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        #[repr(transparent)]
        $vis struct $name(u32);

        #[allow(dead_code, reason = "a crate-private index type uses only some accessors")]
        impl $name {
            /// The one invalid value: "no such item".
            pub const NONE: Self = Self(u32::MAX);

            /// The id of `index` (`u32::MAX` is [`NONE`](Self::NONE)).
            #[must_use]
            pub const fn new(index: u32) -> Self {
                Self(index)
            }

            /// The index, `None` for [`NONE`](Self::NONE).
            #[must_use]
            pub const fn get(self) -> Option<u32> {
                if self.0 == u32::MAX { None } else { Some(self.0) }
            }

            /// Whether this is [`NONE`](Self::NONE).
            #[must_use]
            pub const fn is_none(self) -> bool {
                self.0 == u32::MAX
            }
        }

        impl Default for $name {
            /// [`NONE`](Self::NONE).
            fn default() -> Self {
                Self::NONE
            }
        }
    };
}

index_type! {
    /// A face of a mesh: its index in the file order (CONVENTIONS.md), as
    /// [`DrawItem::face`](crate::DrawItem::face) and the ID colours number faces.
    pub struct FaceId;
}

index_type! {
    /// A planar piece of a [`Geometry`](crate::Geometry) (a face, or one part of a
    /// non-planar face): its index in [`Geometry::pieces`](crate::Geometry::pieces).
    pub struct PieceId;
}

index_type! {
    /// A node of a BSP tree, in pre-order.
    pub(crate) struct NodeId;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn none_is_the_one_invalid_value() {
        assert_eq!(PieceId::new(3).get(), Some(3));
        assert_eq!(PieceId::NONE.get(), None);
        assert!(FaceId::default().is_none());
        assert_eq!(NodeId::new(u32::MAX), NodeId::NONE);
    }
}

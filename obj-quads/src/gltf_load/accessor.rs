//! Accessor checks: type, and bounds against the buffer view and the buffer,
//! before `gltf`'s readers touch the data.

use gltf::Accessor;
use gltf::accessor::{DataType, Dimensions};

use super::gltf_err;
use crate::LoadError;

/// File and object for error messages about one primitive.
pub(super) struct Ctx<'a> {
    pub(super) file: &'a str,
    pub(super) object: &'a str,
}

impl Ctx<'_> {
    /// A [`LoadError::Gltf`] about this primitive.
    pub(super) fn err(&self, detail: &str) -> LoadError {
        gltf_err(self.file, format!("{}: {detail}", self.object))
    }

    /// Checks an accessor's type and that its count of elements lies inside
    /// its buffer view and buffer, so that `gltf`'s readers cannot fail or
    /// panic on it and no count exceeds what the bytes hold.
    pub(super) fn check(
        &self,
        acc: &Accessor<'_>,
        dims: Dimensions,
        types: &[DataType],
        buffers: &[Vec<u8>],
        what: &str,
    ) -> Result<(), LoadError> {
        let fail =
            |detail: String| Err(self.err(&format!("{what} accessor {}: {detail}", acc.index())));
        if acc.dimensions() != dims || !types.contains(&acc.data_type()) {
            return fail(format!(
                "unsupported type {:?} {:?}",
                acc.dimensions(),
                acc.data_type()
            ));
        }
        if acc.sparse().is_some() {
            return fail("sparse accessors are not supported".into());
        }
        let count = acc.count();
        if count == 0 {
            return fail("count is 0".into());
        }
        let Some(view) = acc.view() else {
            return fail("no buffer view".into());
        };
        let elem = acc.size();
        let stride = view.stride().unwrap_or(elem);
        if stride < elem {
            return fail(format!("stride {stride} smaller than element size {elem}"));
        }
        let end = stride
            .checked_mul(count - 1)
            .and_then(|x| x.checked_add(elem))
            .and_then(|x| x.checked_add(acc.offset()));
        if end.is_none_or(|end| end > view.length()) {
            return fail(format!(
                "count {count} overruns its buffer view ({} bytes)",
                view.length()
            ));
        }
        let view_end = view.offset().checked_add(view.length());
        let buffer_len = buffers.get(view.buffer().index()).map_or(0, Vec::len);
        if view_end.is_none_or(|e| e > buffer_len) {
            return fail(format!(
                "buffer view {} overruns buffer {} ({buffer_len} bytes)",
                view.index(),
                view.buffer().index()
            ));
        }
        Ok(())
    }
}

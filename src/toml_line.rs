//! The place a field path such as `objects[2].shape.radius` names in a TOML text, from the
//! parser's own spans: quoted keys (`"radius" = 1`), dotted keys (`shape.radius = 1`), inline
//! tables and arrays split over lines all resolve alike, where matching text by eye did not.

use std::ops::Range;
use toml_edit::{ImDocument, Item, Key, Table, Value};

/// One step of a field path.
enum Step<'a> {
    Key(&'a str),
    Index(usize),
}

/// `a.b[2].c` as steps; `[*]` (any element) ends the path at the array itself.
fn steps(path: &str) -> Vec<Step<'_>> {
    let mut out = Vec::new();
    for part in path.split('.') {
        let (key, rest) = part.split_once('[').unwrap_or((part, ""));
        if !key.is_empty() {
            out.push(Step::Key(key));
        }
        for idx in rest.split('[').map(|s| s.trim_end_matches(']')) {
            match idx.parse() {
                Ok(i) => out.push(Step::Index(i)),
                Err(_) if idx.is_empty() => {}
                Err(_) => return out,
            }
        }
    }
    out
}

/// `:LINE:COL` of the field `path` in `text`, to follow a file name in an error; empty when
/// the file does not say where (see [`place`]).
pub fn suffix(text: &str, path: &str) -> String {
    place(text, path).map_or(String::new(), |(l, c)| format!(":{l}:{c}"))
}

/// Where a step of the path has reached.
#[derive(Clone, Copy)]
enum Node<'a> {
    Table(&'a Table),
    Item(&'a Item),
    Value(&'a Value),
}

impl<'a> Node<'a> {
    fn of(item: &'a Item) -> Node<'a> {
        match item {
            Item::Table(t) => Node::Table(t),
            Item::Value(v) => Node::Value(v),
            other => Node::Item(other),
        }
    }

    /// The span where the step is written and the node it leads to.
    fn step(self, step: &Step) -> Option<(Option<Range<usize>>, Node<'a>)> {
        let keyed = |(key, item): (&'a Key, &'a Item)| (key.span().or_else(|| item.span()), Node::of(item));
        match (self, step) {
            (Node::Table(t), Step::Key(k)) => t.get_key_value(k).map(keyed),
            (Node::Value(Value::InlineTable(t)), Step::Key(k)) => t.get_key_value(k).map(keyed),
            (Node::Item(Item::ArrayOfTables(a)), Step::Index(i)) => a.get(*i).map(|t| (t.span(), Node::Table(t))),
            (Node::Value(Value::Array(a)), Step::Index(i)) => a.get(*i).map(|v| (v.span(), Node::Value(v))),
            _ => None,
        }
    }
}

/// Line and column (1-based) where the field `path` is written in `text`; when the field
/// itself is absent (a default), those of the nearest enclosing element written there (an
/// `[[objects]]` header), and `None` when not even the first step is written or `text` does
/// not parse.
pub fn place(text: &str, path: &str) -> Option<(usize, usize)> {
    let doc = ImDocument::parse(text).ok()?;
    let mut node = Node::Table(doc.as_table());
    let mut at = None;
    for step in steps(path) {
        let Some((span, next)) = node.step(&step) else { break };
        at = span.map(|s| s.start).or(at);
        node = next;
    }
    at.map(|offset| crate::error::line_col(text, offset))
}

#[cfg(test)]
mod tests {
    use super::place;

    fn line_of(text: &str, path: &str) -> Option<usize> {
        place(text, path).map(|(l, _)| l)
    }

    const TEXT: &str = r#"name = "x"
"size" = [
  64,
  48,
]
camera.eye = [0.0, -5.0, 1.5]

[[objects]]
shape = { kind = "sphere", radius = 1.0 }

[[objects]]
shape = { kind = "plane", size = [
    2.0,
    3.0] }
segments = [4, 4]
"#;

    #[test]
    fn quoted_dotted_inline_and_split_fields_resolve_to_their_lines() {
        assert_eq!(line_of(TEXT, "name"), Some(1));
        assert_eq!(line_of(TEXT, "size"), Some(2), "a quoted key");
        assert_eq!(line_of(TEXT, "size[1]"), Some(4), "an element on its own line");
        assert_eq!(line_of(TEXT, "camera.eye"), Some(6), "a dotted key");
        assert_eq!(line_of(TEXT, "objects[0].shape.radius"), Some(9), "inside an inline table");
        assert_eq!(place(TEXT, "objects[0].shape.radius"), Some((9, 28)), "the key's own column");
        assert_eq!(
            line_of(TEXT, "objects[1].shape.size[1]"),
            Some(14),
            "an inline table's array over lines"
        );
        assert_eq!(line_of(TEXT, "objects[1].segments[0]"), Some(15));
        assert_eq!(
            line_of(TEXT, "objects[*].segments"),
            Some(8),
            "any element: the array's first table"
        );
    }

    #[test]
    fn an_absent_field_points_at_its_enclosing_element_and_an_absent_root_at_nothing() {
        assert_eq!(line_of(TEXT, "objects[0].translate"), Some(8));
        assert_eq!(line_of(TEXT, "objects[1].bump.size"), Some(11));
        assert_eq!(line_of(TEXT, "lights[0].colour"), None);
        assert_eq!(line_of("not = [toml", "not"), None);
    }
}

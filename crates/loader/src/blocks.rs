//! block.properties (and item.properties, entity.properties, which share its form): the ids
//! a pack gives the game's blocks, items and entities (`block.10008=water flowing_water`), read
//! through [`crate::properties`] so conditionals and continuations count as they do for the
//! loader.

use std::collections::HashMap;

use crate::properties::Properties;

/// The path of block.properties inside `shaders/`.
pub const BLOCK_PROPERTIES: &str = "block.properties";
/// The file that maps entities to `entityId`s (OptiFine's shaders.txt, "Entity ID mapping").
pub const ENTITY_PROPERTIES: &str = "entity.properties";

/// A block, item or entity name with `minecraft:` added where it has no namespace.
pub fn namespaced(name: &str) -> String {
    if name.contains(':') { name.to_string() } else { format!("minecraft:{name}") }
}

/// `<prefix>.<id>=<names>` entries (`prefix`: `block`, `item` or `entity`): each name, with
/// `minecraft:` added where it has no namespace, to the first id that lists it.
pub fn ids(properties: &Properties, prefix: &str) -> HashMap<String, i32> {
    let mut ids = HashMap::new();
    let prefix = format!("{prefix}.");
    for (id, entry) in properties.with_prefix(&prefix) {
        let Ok(id) = id.parse::<i32>() else { continue };
        for name in entry.value.split_whitespace() {
            ids.entry(namespaced(name)).or_insert(id);
        }
    }
    ids
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_get_their_namespace_and_the_first_id() {
        let p = Properties::parse_plain("block.10008=water flowing_water \\\n  minecraft:ice\nblock.10009=water mod:reeds\nblock.x=stone\n");
        let ids = ids(&p, "block");
        assert_eq!(ids["minecraft:water"], 10008);
        assert_eq!(ids["minecraft:ice"], 10008);
        assert_eq!(ids["mod:reeds"], 10009);
        assert!(!ids.contains_key("minecraft:stone"));
    }
}

//! The open document: the scene, its file, and undo/redo of every edit.

use std::path::PathBuf;

use crate::scene::Scene;

/// How many edits can be undone.
pub const UNDO_DEPTH: usize = 200;

/// The scene being edited, with its history.
#[derive(Debug, Default)]
pub struct Document {
    /// The current scene.
    pub scene: Scene,
    /// Where it was loaded from or last saved to.
    pub path: Option<PathBuf>,
    /// Whether it changed since it was loaded or saved.
    pub dirty: bool,
    undo: Vec<(String, Scene)>,
    redo: Vec<(String, Scene)>,
}

impl Document {
    /// A document for a scene.
    pub fn new(scene: Scene, path: Option<PathBuf>) -> Self {
        Document {
            scene,
            path,
            ..Default::default()
        }
    }

    /// Applies an edit named `what` (shown in the Edit menu). The scene before it is kept
    /// for undo; if the edit fails, the scene is left as it was and the error returned.
    pub fn edit<E>(
        &mut self,
        what: &str,
        f: impl FnOnce(&mut Scene) -> Result<(), E>,
    ) -> Result<(), E> {
        let before = self.scene.clone();
        match f(&mut self.scene) {
            Ok(()) => {
                self.undo.push((what.to_string(), before));
                if self.undo.len() > UNDO_DEPTH {
                    self.undo.remove(0);
                }
                self.redo.clear();
                self.dirty = true;
                Ok(())
            }
            Err(e) => {
                self.scene = before;
                Err(e)
            }
        }
    }

    /// Changes the scene in place without an undo step (for the steps of a drag; call
    /// [`Document::checkpoint`] once before the first).
    pub fn edit_continuing(&mut self, f: impl FnOnce(&mut Scene)) {
        f(&mut self.scene);
        self.dirty = true;
    }

    /// Records the current scene as an undo step named `what` (the start of a drag).
    pub fn checkpoint(&mut self, what: &str) {
        self.undo.push((what.to_string(), self.scene.clone()));
        self.redo.clear();
    }

    /// The name of the edit that undo would revert.
    pub fn undo_name(&self) -> Option<&str> {
        self.undo.last().map(|(n, _)| n.as_str())
    }

    /// The name of the edit that redo would repeat.
    pub fn redo_name(&self) -> Option<&str> {
        self.redo.last().map(|(n, _)| n.as_str())
    }

    /// Reverts the last edit; false when there is none.
    pub fn undo(&mut self) -> bool {
        self.swap(true)
    }

    /// Repeats the last undone edit; false when there is none.
    pub fn redo(&mut self) -> bool {
        self.swap(false)
    }

    fn swap(&mut self, undo: bool) -> bool {
        let (from, to) = if undo {
            (&mut self.undo, &mut self.redo)
        } else {
            (&mut self.redo, &mut self.undo)
        };
        let Some((name, mut scene)) = from.pop() else {
            return false;
        };
        std::mem::swap(&mut scene, &mut self.scene);
        to.push((name, scene));
        // Caches key on revisions: give every object a new one.
        for o in &mut self.scene.objects {
            o.touch();
        }
        self.dirty = true;
        true
    }
}

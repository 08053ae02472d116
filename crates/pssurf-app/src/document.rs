//! The open document: the scene, what is selected in it, its file, and undo/redo of every
//! edit.
//!
//! A history step is a snapshot of the scene taken before the edit. Surfaces are shared
//! (`Arc`), so a snapshot copies pointers and names, not control nets; an edit copies the one
//! surface it changes (copy on write, [`SceneObject::surface_mut`]). Undo swaps the snapshot
//! back with the revisions it had: objects the edit did not touch keep theirs, so the display
//! cache keeps their meshes and re-samples only what changed.
//!
//! [`SceneObject::surface_mut`]: crate::scene::SceneObject::surface_mut

use std::path::PathBuf;

use crate::scene::{FileKind, Scene};

/// How many edits can be undone.
pub const UNDO_DEPTH: usize = 200;

/// What is selected.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Selection {
    /// The selected object.
    pub object: Option<usize>,
    /// The selected vertex (control group) of that object.
    pub vertex: Option<usize>,
}

impl Selection {
    /// Object `i`, no vertex.
    pub fn object(i: usize) -> Self {
        Selection {
            object: Some(i),
            vertex: None,
        }
    }
}

/// One undo or redo step: the scene as it was, and the edit's name for the Edit menu.
#[derive(Debug)]
struct Step {
    name: String,
    scene: Scene,
}

/// The scene being edited, with its selection and history.
#[derive(Debug, Default)]
pub struct Document {
    /// The current scene.
    pub scene: Scene,
    /// What is selected in it.
    pub selection: Selection,
    /// Where it was loaded from or last saved to.
    pub path: Option<PathBuf>,
    /// The kind of that file (a new document is a scene).
    pub kind: FileKind,
    /// Whether it changed since it was loaded or saved.
    pub dirty: bool,
    /// The vertex last selected in each object, by object id: selecting an object again
    /// brings its own vertex back, never another object's.
    vertices: std::collections::HashMap<u64, usize>,
    undo: Vec<Step>,
    redo: Vec<Step>,
}

impl Document {
    /// A document for a scene, with its first object selected.
    pub fn new(scene: Scene, path: Option<PathBuf>) -> Self {
        let selection = if scene.objects.is_empty() {
            Selection::default()
        } else {
            Selection::object(0)
        };
        Document {
            scene,
            selection,
            path,
            ..Default::default()
        }
    }

    /// A document for a scene read from `path`, a file of `kind`.
    pub fn from_file(scene: Scene, path: PathBuf, kind: FileKind) -> Self {
        Document {
            kind,
            ..Document::new(scene, Some(path))
        }
    }

    /// The name shown in the title and in questions: the file name, or "untitled".
    pub fn name(&self) -> String {
        self.path
            .as_deref()
            .map_or_else(|| "untitled".to_string(), crate::files::file_name)
    }

    /// Selects `selection`. Selecting only an object brings back the vertex last selected in
    /// that object (the vertex selection belongs to its object).
    pub fn select(&mut self, selection: Selection) {
        if let Some(o) = self
            .selection
            .object
            .and_then(|i| self.scene.objects.get(i))
            && let Some(v) = self.selection.vertex
        {
            self.vertices.insert(o.id, v);
        }
        let object = selection.object.and_then(|i| self.scene.objects.get(i));
        let vertex = match (selection.vertex, object) {
            (Some(v), Some(o)) => {
                self.vertices.insert(o.id, v);
                Some(v)
            }
            (None, Some(o)) if selection.object != self.selection.object => {
                self.vertices.get(&o.id).copied()
            }
            _ => None,
        };
        let vertex = vertex.filter(|&v| object.is_some_and(|o| v < o.vertex_count()));
        if selection.vertex.is_none()
            && selection.object == self.selection.object
            && let Some(o) = object
        {
            self.vertices.remove(&o.id);
        }
        self.selection = Selection {
            object: selection.object.filter(|_| object.is_some()),
            vertex,
        };
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
                self.push_undo(what, before);
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
        self.push_undo(what, self.scene.clone());
    }

    fn push_undo(&mut self, what: &str, scene: Scene) {
        self.undo.push(Step {
            name: what.to_string(),
            scene,
        });
        if self.undo.len() > UNDO_DEPTH {
            self.undo.remove(0);
        }
        self.redo.clear();
    }

    /// The name of the edit that undo would revert.
    pub fn undo_name(&self) -> Option<&str> {
        self.undo.last().map(|s| s.name.as_str())
    }

    /// The name of the edit that redo would repeat.
    pub fn redo_name(&self) -> Option<&str> {
        self.redo.last().map(|s| s.name.as_str())
    }

    /// Reverts the last edit; false when there is none.
    pub fn undo(&mut self) -> bool {
        let moved = Self::swap(&mut self.scene, &mut self.undo, &mut self.redo);
        self.after_history(moved)
    }

    /// Repeats the last undone edit; false when there is none.
    pub fn redo(&mut self) -> bool {
        let moved = Self::swap(&mut self.scene, &mut self.redo, &mut self.undo);
        self.after_history(moved)
    }

    /// Moves the last step of `from` into the scene, and the scene into `to`.
    fn swap(scene: &mut Scene, from: &mut Vec<Step>, to: &mut Vec<Step>) -> bool {
        let Some(mut step) = from.pop() else {
            return false;
        };
        std::mem::swap(&mut step.scene, scene);
        to.push(step);
        true
    }

    /// Keeps the selection inside the restored scene.
    fn after_history(&mut self, moved: bool) -> bool {
        if !moved {
            return false;
        }
        self.dirty = true;
        let objects = &self.scene.objects;
        match self.selection.object.map(|i| objects.get(i)) {
            Some(None) => self.selection = Selection::default(),
            Some(Some(o)) => {
                let groups = o.vertex_count();
                if self.selection.vertex.is_some_and(|v| v >= groups) {
                    self.selection.vertex = None;
                }
            }
            None => {}
        }
        true
    }
}

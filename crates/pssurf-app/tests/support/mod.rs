//! What the UI tests share: a harness without a GPU, and clicks as a user makes them.

#![allow(dead_code)] // Each test file uses its own part of this module.

use egui::{Event, Modifiers, PointerButton, Pos2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use pssurf_app::App;

/// The application in a 1400 × 900 harness (no GPU), after its first two frames.
pub fn harness(app: App) -> Harness<'static, App> {
    let mut h = Harness::builder()
        .with_size(vec2(1400.0, 900.0))
        .build_ui_state(|ui, app: &mut App| app.ui(ui), app);
    h.run_steps(2);
    h
}

/// Scrolls the widget labelled `label` into view, then clicks it.
pub fn press(h: &mut Harness<'_, App>, label: &str) {
    h.get_by_label(label).scroll_to_me();
    // Scrolling is animated.
    h.run_steps(10);
    h.get_by_label(label).click();
    h.run_steps(3);
}

/// A primary click at a screen position.
pub fn click(h: &mut Harness<'_, App>, pos: Pos2) {
    click_with(h, pos, Modifiers::NONE);
}

/// A primary click at a screen position with `modifiers` held (e.g. Shift).
pub fn click_with(h: &mut Harness<'_, App>, pos: Pos2, modifiers: Modifiers) {
    h.event(Event::PointerMoved(pos));
    h.event(Event::ModifiersChanged(modifiers));
    h.run_steps(1);
    for pressed in [true, false] {
        h.event(Event::PointerButton {
            pos,
            button: PointerButton::Primary,
            pressed,
            modifiers,
        });
        h.run_steps(1);
    }
    h.event(Event::ModifiersChanged(Modifiers::NONE));
    h.run_steps(1);
}

/// A primary-button drag from `from` through `steps` equal moves to `to`, running two frames
/// after each move and calling `each` after it (for what a test watches during the drag).
pub fn drag(
    h: &mut Harness<'_, App>,
    from: Pos2,
    to: Pos2,
    steps: usize,
    mut each: impl FnMut(&mut Harness<'_, App>),
) {
    h.event(Event::PointerMoved(from));
    h.event(Event::PointerButton {
        pos: from,
        button: PointerButton::Primary,
        pressed: true,
        modifiers: Modifiers::NONE,
    });
    h.run_steps(1);
    for k in 1..=steps {
        h.event(Event::PointerMoved(
            from + (to - from) * (k as f32 / steps as f32),
        ));
        h.run_steps(2);
        each(h);
    }
    h.event(Event::PointerButton {
        pos: to,
        button: PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
    h.run_steps(3);
}

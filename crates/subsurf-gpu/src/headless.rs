//! Quiet start-up on machines without a display server.
//!
//! Mesa's implicit Vulkan layer `VK_LAYER_MESA_device_select` orders GPUs by the display
//! they drive. When an application enables the Wayland surface extension (wgpu always does
//! where the driver offers it), the layer connects to a Wayland compositor while the adapters
//! are enumerated; without one, libwayland prints
//! `error: XDG_RUNTIME_DIR is invalid or not set in the environment.` on stderr for every
//! instance, although nothing failed. With no display server there is no display to select
//! by, so the layer has nothing to do: [`disable_display_layers_when_headless`] switches it
//! off through its documented `NODEVICE_SELECT=1` variable. Every instance the library
//! creates ([`crate::GpuContext::new`], [`crate::context::list_adapters`]) does this first, once per
//! process, so that a program using the library directly stays quiet too.

/// The environment variable that disables Mesa's device-select layer.
pub const NODEVICE_SELECT: &str = "NODEVICE_SELECT";

/// Whether the environment names a display server (`WAYLAND_DISPLAY` or `DISPLAY`).
pub fn has_display_server() -> bool {
    ["WAYLAND_DISPLAY", "DISPLAY"]
        .iter()
        .any(|v| std::env::var_os(v).is_some_and(|s| !s.is_empty()))
}

/// Sets `NODEVICE_SELECT=1` when no display server is named and the variable is not set
/// already; returns whether it did. Changing the environment is only sound while no other
/// thread reads it: call this at the start of `main`, before any thread is spawned (the
/// `subsurf` command line does). A user's own `NODEVICE_SELECT` is left as it is.
pub fn disable_display_layers_when_headless() -> bool {
    if has_display_server() || std::env::var_os(NODEVICE_SELECT).is_some() {
        return false;
    }
    std::env::set_var(NODEVICE_SELECT, "1");
    true
}

/// [`disable_display_layers_when_headless`], once per process: called before the library
/// creates a wgpu instance. Setting the variable while other threads run is sound for Rust
/// readers (the standard library serialises its environment access); the Vulkan loader reads
/// it only while an instance is created, and every instance the library creates waits for
/// this to finish first.
pub(crate) fn quiet_once() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        disable_display_layers_when_headless();
    });
}

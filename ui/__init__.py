"""What the artist sees: scene settings (properties), sidebar panels, Add menus, and the
registration of every class (operators included)."""

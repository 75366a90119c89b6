"""How scenes look (appearance only, never physics): procedural textures, materials, the room and
its light."""

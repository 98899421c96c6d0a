#version 330 core
// Depth-only fragment stage (after mesh.vert): Points mode first lays down the surface's
// depth, with colour writes off, so that the surface hides the points behind it.

void main() {}

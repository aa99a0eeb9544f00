#version 450 core
// Depth only (the sun's shadow map).
void main() {}

#version 450
// raykit bench — depth_only.frag: the fragment stage of the depth pre-pass (colour writes are
// masked off; the depth comes from the material's own vertex stage, declared invariant).
void main() {}

#version 450

// Depth only: nothing to write.
void main()
{
}

// Depth only: the light pass's depth map has no colour.
void main()
{
}

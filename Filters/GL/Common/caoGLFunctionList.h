/**
 * caoGLFunctionList — the OpenGL 4.3 entry points the compute layer uses,
 * as an X-macro: CAO_GL_FUNCTIONS(X) calls X(Name, PFN type suffix) once
 * per function. It includes no GL header, so that a translation unit built
 * against another GL loader (VTK's GLEW, in vtkCAOWindowGL.cxx) can expand
 * the same list: the declaration, the loaders and the GLEW bridge cannot
 * drift apart.
 */
#ifndef caoGLFunctionList_h
#define caoGLFunctionList_h

#define CAO_GL_FUNCTIONS(X)                                                                      \
  X(ActiveTexture, ACTIVETEXTURE)                                                                \
  X(AttachShader, ATTACHSHADER)                                                                  \
  X(BeginQuery, BEGINQUERY)                                                                      \
  X(BindBuffer, BINDBUFFER)                                                                      \
  X(BindBufferBase, BINDBUFFERBASE)                                                              \
  X(BindFramebuffer, BINDFRAMEBUFFER)                                                            \
  X(BindImageTexture, BINDIMAGETEXTURE)                                                          \
  X(BindTexture, BINDTEXTURE)                                                                    \
  X(BindVertexArray, BINDVERTEXARRAY)                                                            \
  X(BlitFramebuffer, BLITFRAMEBUFFER)                                                            \
  X(BlendEquationSeparate, BLENDEQUATIONSEPARATE)                                                \
  X(BlendFuncSeparate, BLENDFUNCSEPARATE)                                                        \
  X(BufferData, BUFFERDATA)                                                                      \
  X(BufferSubData, BUFFERSUBDATA)                                                                \
  X(CheckFramebufferStatus, CHECKFRAMEBUFFERSTATUS)                                              \
  X(ClearBufferfv, CLEARBUFFERFV)                                                                \
  X(ClearBufferData, CLEARBUFFERDATA)                                                            \
  X(ColorMask, COLORMASK)                                                                        \
  X(CompileShader, COMPILESHADER)                                                                \
  X(CopyBufferSubData, COPYBUFFERSUBDATA)                                                        \
  X(CopyTexSubImage2D, COPYTEXSUBIMAGE2D)                                                        \
  X(CreateProgram, CREATEPROGRAM)                                                                \
  X(CreateShader, CREATESHADER)                                                                  \
  X(DeleteBuffers, DELETEBUFFERS)                                                                \
  X(DeleteFramebuffers, DELETEFRAMEBUFFERS)                                                      \
  X(DeleteProgram, DELETEPROGRAM)                                                                \
  X(DeleteQueries, DELETEQUERIES)                                                                \
  X(DeleteShader, DELETESHADER)                                                                  \
  X(DeleteTextures, DELETETEXTURES)                                                              \
  X(DeleteVertexArrays, DELETEVERTEXARRAYS)                                                      \
  X(DepthMask, DEPTHMASK)                                                                        \
  X(Disable, DISABLE)                                                                            \
  X(DisableVertexAttribArray, DISABLEVERTEXATTRIBARRAY)                                          \
  X(DispatchCompute, DISPATCHCOMPUTE)                                                            \
  X(DrawBuffers, DRAWBUFFERS)                                                                    \
  X(DrawArrays, DRAWARRAYS)                                                                      \
  X(DrawArraysInstanced, DRAWARRAYSINSTANCED)                                                    \
  X(Enable, ENABLE)                                                                              \
  X(EnableVertexAttribArray, ENABLEVERTEXATTRIBARRAY)                                            \
  X(EndQuery, ENDQUERY)                                                                          \
  X(Finish, FINISH)                                                                              \
  X(Flush, FLUSH)                                                                                \
  X(FramebufferParameteri, FRAMEBUFFERPARAMETERI)                                                \
  X(FramebufferTexture2D, FRAMEBUFFERTEXTURE2D)                                                  \
  X(GenBuffers, GENBUFFERS)                                                                      \
  X(GenFramebuffers, GENFRAMEBUFFERS)                                                            \
  X(GenQueries, GENQUERIES)                                                                      \
  X(GenTextures, GENTEXTURES)                                                                    \
  X(GenVertexArrays, GENVERTEXARRAYS)                                                            \
  X(GetBooleanv, GETBOOLEANV)                                                                    \
  X(GetBufferSubData, GETBUFFERSUBDATA)                                                          \
  X(GetError, GETERROR)                                                                          \
  X(GetFramebufferAttachmentParameteriv, GETFRAMEBUFFERATTACHMENTPARAMETERIV)                    \
  X(GetIntegeri_v, GETINTEGERI_V)                                                                \
  X(GetIntegerv, GETINTEGERV)                                                                    \
  X(GetProgramInfoLog, GETPROGRAMINFOLOG)                                                        \
  X(GetProgramiv, GETPROGRAMIV)                                                                  \
  X(GetQueryObjectui64v, GETQUERYOBJECTUI64V)                                                    \
  X(GetShaderInfoLog, GETSHADERINFOLOG)                                                          \
  X(GetShaderiv, GETSHADERIV)                                                                    \
  X(GetString, GETSTRING)                                                                        \
  X(GetTexImage, GETTEXIMAGE)                                                                    \
  X(GetTexLevelParameteriv, GETTEXLEVELPARAMETERIV)                                              \
  X(GetUniformLocation, GETUNIFORMLOCATION)                                                      \
  X(IsBuffer, ISBUFFER)                                                                          \
  X(IsEnabled, ISENABLED)                                                                        \
  X(IsFramebuffer, ISFRAMEBUFFER)                                                                \
  X(IsProgram, ISPROGRAM)                                                                        \
  X(IsQuery, ISQUERY)                                                                            \
  X(IsTexture, ISTEXTURE)                                                                        \
  X(IsVertexArray, ISVERTEXARRAY)                                                                \
  X(LinkProgram, LINKPROGRAM)                                                                    \
  X(MemoryBarrier, MEMORYBARRIER)                                                                \
  X(PixelStorei, PIXELSTOREI)                                                                    \
  X(QueryCounter, QUERYCOUNTER)                                                                  \
  X(ReadBuffer, READBUFFER)                                                                      \
  X(ReadPixels, READPIXELS)                                                                      \
  X(Scissor, SCISSOR)                                                                            \
  X(ShaderSource, SHADERSOURCE)                                                                  \
  X(TexImage2D, TEXIMAGE2D)                                                                      \
  X(TexParameteri, TEXPARAMETERI)                                                                \
  X(TexStorage2D, TEXSTORAGE2D)                                                                  \
  X(TexStorage3D, TEXSTORAGE3D)                                                                  \
  X(TexSubImage2D, TEXSUBIMAGE2D)                                                                \
  X(TexSubImage3D, TEXSUBIMAGE3D)                                                                \
  X(TextureView, TEXTUREVIEW)                                                                    \
  X(Uniform1f, UNIFORM1F)                                                                        \
  X(Uniform1i, UNIFORM1I)                                                                        \
  X(Uniform1ui, UNIFORM1UI)                                                                      \
  X(Uniform2d, UNIFORM2D)                                                                        \
  X(Uniform2f, UNIFORM2F)                                                                        \
  X(Uniform2i, UNIFORM2I)                                                                        \
  X(Uniform3d, UNIFORM3D)                                                                        \
  X(Uniform3f, UNIFORM3F)                                                                        \
  X(Uniform3i, UNIFORM3I)                                                                        \
  X(Uniform4i, UNIFORM4I)                                                                      \
  X(Uniform4f, UNIFORM4F)                                                                        \
  X(UseProgram, USEPROGRAM)                                                                      \
  X(VertexAttribDivisor, VERTEXATTRIBDIVISOR)                                                    \
  X(VertexAttribIPointer, VERTEXATTRIBIPOINTER)                                                  \
  X(VertexAttribPointer, VERTEXATTRIBPOINTER)                                                    \
  X(Viewport, VIEWPORT)

#endif

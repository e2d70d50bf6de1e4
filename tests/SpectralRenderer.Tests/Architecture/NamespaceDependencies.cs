using System.Collections.Immutable;
using System.Reflection;
using System.Reflection.Emit;
using System.Reflection.Metadata;
using System.Reflection.Metadata.Ecma335;
using System.Reflection.PortableExecutable;

namespace SpectralRenderer.Tests.Architecture;

/// <summary>
/// The namespace dependency graph of a compiled assembly, read from its metadata (ECMA-335): for every type, the
/// namespaces of the types its base type, interfaces, fields, method signatures, local variables and method bodies
/// (every type, method and field token in the IL) refer to. It sees what the compiler resolved, so a dependency counts
/// whether the source wrote a using directive or a fully qualified name; an unused using directive is no dependency.
/// </summary>
public static class NamespaceDependencies
{
    /// <summary>Edges from each namespace of <paramref name="assemblyPath"/> to the namespaces it uses (itself excluded).</summary>
    public static Dictionary<string, SortedSet<string>> Read(string assemblyPath)
    {
        using var pe = new PEReader(File.OpenRead(assemblyPath));
        var md = pe.GetMetadataReader();
        var graph = new Dictionary<string, SortedSet<string>>(StringComparer.Ordinal);
        foreach (var handle in md.TypeDefinitions)
        {
            var from = NamespaceOf(md, handle);
            if (from.Length == 0) continue;   // <Module>, <PrivateImplementationDetails>
            var to = new HashSet<string>(StringComparer.Ordinal);
            var provider = new Collector(md, to);
            var type = md.GetTypeDefinition(handle);
            Add(md, type.BaseType, provider);
            foreach (var i in type.GetInterfaceImplementations()) Add(md, md.GetInterfaceImplementation(i).Interface, provider);
            foreach (var f in type.GetFields()) md.GetFieldDefinition(f).DecodeSignature(provider, null);
            foreach (var p in type.GetProperties()) md.GetPropertyDefinition(p).DecodeSignature(provider, null);
            foreach (var m in type.GetMethods())
            {
                var method = md.GetMethodDefinition(m);
                method.DecodeSignature(provider, null);
                if (method.RelativeVirtualAddress == 0) continue;
                var body = pe.GetMethodBody(method.RelativeVirtualAddress);
                if (!body.LocalSignature.IsNil)
                    md.GetStandaloneSignature(body.LocalSignature).DecodeLocalSignature(provider, null);
                foreach (var token in Tokens(body.GetILBytes() ?? []))
                    Add(md, MetadataTokens.EntityHandle(token), provider);
            }
            if (!graph.TryGetValue(from, out var edges)) graph[from] = edges = new SortedSet<string>(StringComparer.Ordinal);
            foreach (var ns in to) if (ns != from) edges.Add(ns);
        }
        return graph;
    }

    static void Add(MetadataReader md, EntityHandle h, Collector c)
    {
        if (h.IsNil) return;
        switch (h.Kind)
        {
            case HandleKind.TypeDefinition: c.GetTypeFromDefinition(md, (TypeDefinitionHandle)h, 0); break;
            case HandleKind.TypeReference: c.GetTypeFromReference(md, (TypeReferenceHandle)h, 0); break;
            case HandleKind.TypeSpecification: md.GetTypeSpecification((TypeSpecificationHandle)h).DecodeSignature(c, null); break;
            case HandleKind.MethodDefinition:
                var m = md.GetMethodDefinition((MethodDefinitionHandle)h);
                c.GetTypeFromDefinition(md, m.GetDeclaringType(), 0);
                m.DecodeSignature(c, null);
                break;
            case HandleKind.FieldDefinition:
                var f = md.GetFieldDefinition((FieldDefinitionHandle)h);
                c.GetTypeFromDefinition(md, f.GetDeclaringType(), 0);
                f.DecodeSignature(c, null);
                break;
            case HandleKind.MemberReference:
                var r = md.GetMemberReference((MemberReferenceHandle)h);
                Add(md, r.Parent, c);
                if (r.GetKind() == MemberReferenceKind.Method) r.DecodeMethodSignature(c, null); else r.DecodeFieldSignature(c, null);
                break;
            case HandleKind.MethodSpecification:
                var s = md.GetMethodSpecification((MethodSpecificationHandle)h);
                Add(md, s.Method, c);
                s.DecodeSignature(c, null);
                break;
        }
    }

    /// <summary>The namespace of a type definition; a nested type has its outermost declaring type's.</summary>
    static string NamespaceOf(MetadataReader md, TypeDefinitionHandle h)
    {
        var t = md.GetTypeDefinition(h);
        while (t.IsNested) t = md.GetTypeDefinition(t.GetDeclaringType());
        return md.GetString(t.Namespace);
    }

    static string NamespaceOf(MetadataReader md, TypeReferenceHandle h)
    {
        var t = md.GetTypeReference(h);
        while (t.ResolutionScope.Kind == HandleKind.TypeReference) t = md.GetTypeReference((TypeReferenceHandle)t.ResolutionScope);
        return md.GetString(t.Namespace);
    }

    /// <summary>Metadata tokens in an IL stream: the operands of the instructions whose operand is a token.</summary>
    static IEnumerable<int> Tokens(byte[] il)
    {
        int i = 0;
        while (i < il.Length)
        {
            ushort code = il[i++];
            if (code == 0xFE) code = (ushort)(0xFE00 | il[i++]);
            var op = OpCodesByValue[code];
            switch (op.OperandType)
            {
                case OperandType.InlineTok or OperandType.InlineType or OperandType.InlineMethod or OperandType.InlineField:
                    yield return BitConverter.ToInt32(il, i); i += 4; break;
                case OperandType.InlineSwitch:
                    int n = BitConverter.ToInt32(il, i); i += 4 + 4 * n; break;
                case OperandType.InlineNone: break;
                case OperandType.ShortInlineBrTarget or OperandType.ShortInlineI or OperandType.ShortInlineVar: i += 1; break;
                case OperandType.InlineVar: i += 2; break;
                case OperandType.InlineI8 or OperandType.InlineR: i += 8; break;
                default: i += 4; break;   // InlineBrTarget, InlineI, InlineSig, InlineString, ShortInlineR
            }
        }
    }

    static readonly Dictionary<ushort, OpCode> OpCodesByValue = typeof(OpCodes).GetFields(BindingFlags.Public | BindingFlags.Static)
        .Select(f => (OpCode)f.GetValue(null)!).ToDictionary(o => (ushort)o.Value);

    /// <summary>Decodes signatures, recording the namespace of every type it meets.</summary>
    sealed class Collector(MetadataReader md, HashSet<string> seen) : ISignatureTypeProvider<int, object?>
    {
        public int GetTypeFromDefinition(MetadataReader reader, TypeDefinitionHandle handle, byte rawTypeKind)
        {
            seen.Add(NamespaceOf(md, handle));
            return 0;
        }
        public int GetTypeFromReference(MetadataReader reader, TypeReferenceHandle handle, byte rawTypeKind)
        {
            seen.Add(NamespaceOf(md, handle));
            return 0;
        }
        public int GetTypeFromSpecification(MetadataReader reader, object? context, TypeSpecificationHandle handle, byte rawTypeKind) =>
            md.GetTypeSpecification(handle).DecodeSignature(this, context);
        public int GetPrimitiveType(PrimitiveTypeCode typeCode) => 0;
        public int GetSZArrayType(int elementType) => 0;
        public int GetArrayType(int elementType, ArrayShape shape) => 0;
        public int GetByReferenceType(int elementType) => 0;
        public int GetPointerType(int elementType) => 0;
        public int GetPinnedType(int elementType) => 0;
        public int GetGenericInstantiation(int genericType, ImmutableArray<int> typeArguments) => 0;
        public int GetGenericMethodParameter(object? context, int index) => 0;
        public int GetGenericTypeParameter(object? context, int index) => 0;
        public int GetFunctionPointerType(MethodSignature<int> signature) => 0;
        public int GetModifiedType(int modifier, int unmodifiedType, bool isRequired) => 0;
    }
}
